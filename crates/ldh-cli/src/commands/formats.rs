//! `ldh formats`: list the built-in vendor formats or print one's TOML file (comments included).

use std::process::ExitCode;

use ldh_core::io::FormatSpec;

/// Run `ldh formats [NAME]`.
pub fn run(name: Option<String>) -> anyhow::Result<ExitCode> {
    match name {
        None => {
            for f in FormatSpec::builtins() {
                println!("{:<20} {}", f.name, f.description);
            }
        }
        // The shipped file's own text, comments on mounting included; a map file as written.
        Some(n) => match FormatSpec::builtin_text(&n) {
            Some(text) => print!("{text}"),
            None => {
                super::resolve_format(&n)?;
                let path = std::path::Path::new(&n);
                let what = "a column map (format TOML)";
                let max = ldh_core::io::MAX_FORMAT_MB;
                print!("{}", ldh_core::io::read_text_limited(path, max, what)?)
            }
        },
    }
    Ok(ExitCode::SUCCESS)
}
