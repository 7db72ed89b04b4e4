//! The change of daily walking between two monitoring periods (`ldh_core::monitor::change`):
//! the noise limit, the judgement, and its withholding with fewer than two valid days.

use ldh_core::monitor::change::visit_change;
use ldh_core::monitor::visit_changes;
use ldh_test_support::monitor_period;

#[test]
fn a_change_beyond_the_days_spread_is_marked_and_one_inside_it_is_not() {
    let before = monitor_period("P1", "pre", &[4000.0, 4400.0, 3600.0]);
    let after = monitor_period("P1", "post", &[6000.0, 6400.0, 5600.0]);
    let c = visit_changes(&[before.clone(), after]);
    assert_eq!(c.len(), 4);
    let steps = &c[1];
    assert_eq!(
        (steps.from_visit.as_str(), steps.to_visit.as_str()),
        ("pre", "post")
    );
    assert!((steps.change - 2000.0).abs() < 1e-9);
    // SD 400 in each: 1.96·√(2·400²/3) = 640.
    assert!((steps.noise - 640.1).abs() < 0.1, "{}", steps.noise);
    assert_eq!(steps.beyond_noise, Some(true));
    let same = visit_change(
        &before,
        &monitor_period("P1", "post", &[4200.0, 3800.0, 4500.0]),
    );
    assert_eq!(same[1].beyond_noise, Some(false));
    // Bouts do not vary at all: any change is beyond, none is not.
    assert_eq!(same[2].beyond_noise, Some(false));
    // Cadence is measured on no day: withheld with the reason.
    assert_eq!(same[3].beyond_noise, None);
    assert!(
        same[3].withheld.contains("0 and 0 valid day(s)"),
        "{}",
        same[3].withheld
    );
}

#[test]
fn one_valid_day_withholds_the_judgement() {
    let c = visit_change(
        &monitor_period("P1", "a", &[5000.0]),
        &monitor_period("P1", "b", &[9000.0, 8000.0]),
    );
    assert_eq!(c[1].beyond_noise, None);
    assert!(c[1].withheld.contains("1 and 2 valid day(s)"));
    assert!((c[1].change - 3500.0).abs() < 1e-9);
}
