//! Partial channel faults ([`super::faults`]) on the real HuGaDB walks (when present): none may
//! be found on a clean recording. (Simulated walks with a fault injected: `ldh-sim`'s
//! tests/analysis/quality_faults.rs.)

use super::super::*;
use super::hugadb::{hugadb_dir, read_hugadb};

/// No false fault on the real walks: every shank of the 18 HuGaDB files (the corrupted
/// gyroscopes clip at their range, which is clipping, not a partial fault).
#[test]
fn hugadb_real_walks_have_no_partial_fault() {
    let Some(dir) = hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "txt"))
        .collect();
    files.sort();
    let mut found = Vec::new();
    for f in &files {
        let (right, left) = read_hugadb(f);
        for (side, rec) in [("right", right), ("left", left)] {
            for x in detect_faults(&rec) {
                found.push(format!("{} {side}: {}", f.display(), x.describe()));
            }
        }
    }
    println!("{} HuGaDB files, faults: {found:?}", files.len());
    assert!(found.is_empty(), "{found:#?}");
}
