//! The recording's start date and time (`start_time.rs`): the spellings parsed, and files that
//! give it in a header comment (ldh `#`, Xsens `//`), in Xsens' UTC columns, as ISO 8601 or
//! Unix timestamps, read onto the recording and the read report; a file without one has none.

use super::super::start_time::{start_in_comment, DateTime};

fn dt(ymd: (i64, i64, i64), hms: (i64, i64, i64), utc: bool) -> DateTime {
    DateTime::new(ymd, hms, utc).unwrap()
}

#[test]
fn date_time_spellings_parse_and_bad_ones_do_not() {
    let at = dt((2024, 3, 5), (10, 21, 33), true);
    let local = DateTime { utc: false, ..at };
    for (text, want) in [
        ("2024-03-05T10:21:33Z", at),
        ("2024-03-05 10:21:33 UTC", at),
        ("2024-03-05T11:21:33+01:00", at),
        ("2024-03-05T05:21:33-0500", at),
        ("2024-03-05T10:21:33.250Z", at),
        ("2024-03-05 10:21:33", local),
        ("2024/03/05 10:21:33", local),
        ("2024-03-05 10:21:33:250", local),
        ("2024-03-05T10:21", DateTime { second: 0, ..local }),
    ] {
        assert_eq!(text.parse::<DateTime>(), Ok(want), "{text}");
    }
    for bad in [
        "2024-02-30 10:00:00",
        "1969-12-31 23:59:59",
        "2024-03-05",
        "yesterday 10:00",
        "2024-03-05 25:00:00",
        "2024-03-05T10:21:33+xx",
    ] {
        assert!(bad.parse::<DateTime>().is_err(), "{bad}");
    }
    assert_eq!(at.iso(), "2024-03-05T10:21:33Z");
    assert_eq!(local.iso(), "2024-03-05T10:21:33");
    assert_eq!(at.to_minute(), "2024-03-05 10:21 UTC");
    assert_eq!(at.iso().parse::<DateTime>(), Ok(at));
    assert_eq!(DateTime::from_unix_s(1_709_634_093.9), Some(at));
    assert_eq!(
        DateTime::from_unix_s(951_782_400.0),
        Some(dt((2000, 2, 29), (0, 0, 0), true))
    );
    assert_eq!(DateTime::from_unix_s(-1.0), None);
}

#[test]
fn start_comments_are_recognised_by_their_key_only() {
    let at = dt((2024, 3, 5), (10, 21, 33), false);
    assert_eq!(
        start_in_comment("// Start Time: 2024-03-05 10:21:33"),
        Some(at)
    );
    assert_eq!(
        start_in_comment("# start: 2024-03-05T10:21:33Z"),
        Some(DateTime { utc: true, ..at })
    );
    assert_eq!(
        start_in_comment("% date = \"2024-03-05 10:21:33\""),
        Some(at)
    );
    assert_eq!(start_in_comment("# exported: 2024-03-05 10:21:33"), None);
    assert_eq!(start_in_comment("// Start Time: soon"), None);
    assert_eq!(start_in_comment("time_s,acc_x,acc_y"), None);
}
