//! Column maps on whole files: unit-suffixed names, alternatives, multi-sensor files (HuGaDB
//! layout), selection by number, duplicates, `#` lines, and the refused maps.

use super::super::format::*;

#[test]
fn shipped_texts_keep_their_comments() {
    for name in BUILTIN_FORMATS {
        let text = FormatSpec::builtin_text(name).unwrap();
        assert!(text.starts_with('#'), "{name}");
        assert_eq!(
            FormatSpec::from_toml_str(text, name).unwrap(),
            FormatSpec::builtin(name).unwrap()
        );
    }
    assert!(FormatSpec::builtin_text("xsens-mtmanager")
        .unwrap()
        .contains("cable pointing down"));
    assert!(FormatSpec::builtin_text("nope").is_none());
}
