//! What the per-leg benchmarks share (`benches/pipeline.rs` group `leg_30s`, `benches/leg_cpu.rs`).

use ldh_core::io::FormatSpec;
use ldh_sim::CohortParams;

/// The left-leg CSV of one simulated healthy subject, 30 s at 100 Hz (seed 17), as `ldh
/// analyze` would read it from disk.
pub fn leg_30s_csv() -> Vec<u8> {
    let c = CohortParams {
        healthy: 1,
        ldh: 0,
        seed: 17,
        duration_s: 30.0,
        ..CohortParams::default()
    };
    let s = c.simulate(0).expect("simulate");
    let dir = std::env::temp_dir().join(format!("ldh-bench-leg30-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    s.write(&dir, &FormatSpec::default()).expect("write");
    let bytes = std::fs::read(dir.join("left.csv")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    bytes
}
