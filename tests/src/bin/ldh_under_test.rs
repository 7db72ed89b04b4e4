fn main() -> std::process::ExitCode {
    ldh_cli::run(std::env::args_os())
}
