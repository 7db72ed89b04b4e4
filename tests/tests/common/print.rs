//! Printing pages with headless Chromium (installed by `.ci/run`): find it, run it, count the
//! A4 pages of the PDF it prints; where tests leave files for people to look at; the real
//! recordings (`../shared/realdata`, read in place, never copied).

use std::path::{Path, PathBuf};

/// Chromium on this machine, if any.
pub fn chromium() -> Option<PathBuf> {
    for c in ["chromium", "chromium-browser", "google-chrome"] {
        if let Ok(o) = std::process::Command::new("which").arg(c).output() {
            if o.status.success() {
                return Some(PathBuf::from(String::from_utf8_lossy(&o.stdout).trim()));
            }
        }
    }
    None
}

/// Headless Chromium on a page, killed after 120 s.
pub fn run_chromium(chrome: &Path, args: &[&str], page: &Path) -> std::process::Output {
    std::process::Command::new("timeout")
        .arg("120")
        .arg(chrome)
        .args(["--headless", "--no-sandbox", "--disable-gpu"])
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap()
}

/// Pages of a PDF printed by Chromium (the page tree's largest `/Count`).
pub fn pdf_pages(bytes: &[u8]) -> usize {
    let s = String::from_utf8_lossy(bytes);
    s.match_indices("/Count ")
        .filter_map(|(i, _)| {
            let digits: String = s[i + 7..]
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            digits.parse().ok()
        })
        .max()
        .unwrap_or(0)
}

/// `page` printed to `pdf` (A4, no header or footer): its number of pages.
pub fn print_to_pdf(chrome: &Path, page: &Path, pdf: &Path) -> usize {
    let o = run_chromium(
        chrome,
        &[
            "--no-pdf-header-footer",
            &format!("--print-to-pdf={}", pdf.display()),
        ],
        page,
    );
    assert!(o.status.success(), "{}", super::text(&o));
    pdf_pages(&std::fs::read(pdf).unwrap())
}

/// Where tests leave files for people to look at: `target/test-artifacts/`.
pub fn artefact_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../target"));
    let d = target.join("test-artifacts");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `../shared/realdata/<name>` from the workspace root (or `$LDH_REALDATA/<name>`; a worktree
/// two levels down also finds `../../shared`), when it holds its `PROVENANCE.md`.
pub fn realdata(name: &str) -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut c: Vec<PathBuf> = Vec::new();
    if let Some(d) = std::env::var_os("LDH_REALDATA") {
        c.push(PathBuf::from(d).join(name));
    }
    c.push(root.join("../shared/realdata").join(name));
    c.push(root.join("../../shared/realdata").join(name));
    c.into_iter().find(|d| d.join("PROVENANCE.md").is_file())
}
