use super::*;

#[test]
fn the_error_is_small_enough_to_return_by_value() {
    // clippy's result_large_err threshold is 128 bytes; every `Result` carries this.
    assert!(
        std::mem::size_of::<LdhError>() < 128,
        "{}",
        std::mem::size_of::<LdhError>()
    );
}

#[test]
fn locations_print_as_an_editor_shows_them() {
    assert_eq!(Location::cell("a.csv", 3, 2).to_string(), "a.csv:3:2");
    assert_eq!(Location::line("a.csv", 7).to_string(), "a.csv:7");
    assert_eq!(Location::file("a.csv").to_string(), "a.csv");
}

#[test]
fn library_errors_convert_with_their_context() {
    let e: LdhError = serde_json::from_str::<u32>("x").unwrap_err().into();
    assert!(e.to_string().starts_with("json: "), "{e}");
    assert_eq!(e.kind(), ErrorKind::Data);
}

#[test]
fn echoed_values_are_cut_with_their_length() {
    assert_eq!(clip("short"), "short");
    let v = "é".repeat(ECHO_CHARS);
    assert_eq!(clip(&v), v.as_str());
    let long = format!("{v}x");
    assert_eq!(clip(&long), format!("{v}… ({} characters)", ECHO_CHARS + 1));
    let e = LdhError::NotANumber {
        loc: Location::cell("a.csv", 3, 2),
        column: "c".repeat(10_000),
        value: "v".repeat(50_000_000),
        hint: String::new(),
    };
    let m = e.to_string();
    assert!(m.len() < 300, "{}", m.len());
    assert!(
        m.contains("… (50000000 characters)' is not a number"),
        "{m}"
    );
    let e = LdhError::DuplicateColumn {
        loc: Location::line("a.csv", 1),
        column: "a".into(),
        positions: (1..100_000).collect(),
    };
    assert!(e.to_string().contains("… (99999 in all)"), "{e}");
    let e = LdhError::param("x", "1".repeat(1_000_000), "r".repeat(1_000_000));
    assert!(e.to_string().len() < 1000);
}
