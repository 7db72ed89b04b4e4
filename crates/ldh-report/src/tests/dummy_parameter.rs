//! The dummy parameter on the report (issue 48): with this crate's test-only feature
//! `dummy-parameter` (ldh-core's, forwarded), `Parameter::Dummy` exists with only its definition
//! and computation in ldh-core, and nothing of this crate names it. It is a row of the subject
//! page's parameter table (the page's rows are `verdict::quantities`, every parameter), below;
//! `tests::vocabulary` checks, for every parameter of `Parameter::ALL` and so for the dummy
//! too, its row of the reliability table (code, unit, its Markdown's `| dummy (DUM, s) |`), its
//! columns in the dictionary and its line of the page's layout. (ldh-core's own dummy test
//! computes the reliability table from repeated trials.)
//!
//! `cargo test --profile ci -p ldh-report --features dummy-parameter --lib dummy_parameter vocabulary`

use super::*;

#[test]
fn dummy_parameter_is_a_row_of_the_subject_page() {
    let d = Parameter::Dummy;
    let p = ReportParams::default().check().unwrap();
    let mut recs = vec![row("J", "ldh", "left", 1.2), row("J", "ldh", "right", 1.2)];
    for (r, v) in recs.iter_mut().zip([2.25, 2.75]) {
        r.set_value(d, Some(v));
    }
    let s = SubjectReport {
        subject_id: "J".into(),
        recordings: recs,
        ..Default::default()
    };
    let html = subject_html(&s, &Reference::published(&p), &p).unwrap();
    // Its code and name, its unit, each side's value.
    let at = html
        .find("<td>DUM — Dummy</td><td>s</td>")
        .unwrap_or_else(|| panic!("no dummy row on the page: {html}"));
    let tr = &html[at..at + html[at..].find("</tr>").unwrap()];
    assert!(tr.contains("2.25") && tr.contains("2.75"), "{tr}");
}
