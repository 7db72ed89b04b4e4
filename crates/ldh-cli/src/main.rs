//! The `ldh` binary: everything is in the `ldh_cli` library so end-to-end tests run the same code.

fn main() -> std::process::ExitCode {
    ldh_cli::run(std::env::args_os())
}
