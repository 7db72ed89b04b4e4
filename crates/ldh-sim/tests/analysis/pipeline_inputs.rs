//! Manifests (csv crate, columns, refusals), subject ids of files given directly, and trials
//! averaged per person before the statistics and the classifiers.

use ldh_core::pipeline::*;
use ldh_core::recording::Setting;

fn manifest(text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let d = tempfile::tempdir().unwrap();
    let m = d.path().join("manifest.csv");
    std::fs::write(&m, text).unwrap();
    (d, m)
}

#[test]
fn trials_are_kept_together_and_ids_of_direct_files_come_from_their_names() {
    let (_d, m) = manifest(
        "subject_id,trial_id,group,affected_side,left,right\n\
         P1,t1,ldh,left,a,b\nP2,t1,healthy,none,c,d\nP1,t2,ldh,left,e,f\n",
    );
    let v = discover(&[m]).unwrap();
    let ids: Vec<(&str, Option<&str>)> = v
        .iter()
        .map(|s| (s.subject_id.as_str(), s.trial_id.as_deref()))
        .collect();
    assert_eq!(
        ids,
        [("P1", Some("t1")), ("P1", Some("t2")), ("P2", Some("t1"))]
    );
    // Counted as people and trials, never as "3 subjects".
    let who = PeopleTrials::of(&v);
    assert_eq!((who.people, who.trials), (2, 3));
    assert_eq!(who.describe(), "2 people, 3 trials");
    assert_eq!(PeopleTrials::of(&v[..1]).describe(), "1 person");
    assert_eq!(PeopleTrials::of(&v[1..]).describe(), "2 people");
    let d = tempfile::tempdir().unwrap();
    let p = |n: &str| {
        let f = d.path().join("exported000").join(n);
        std::fs::create_dir_all(f.parent().unwrap()).unwrap();
        std::fs::write(&f, "x").unwrap();
        f
    };
    for (a, b, want) in [
        ("P07_left.csv", "P07_right.csv", "P07"),
        ("left-P07.csv", "right-P07.csv", "P07"),
        (
            "HuGaDB_v1_walking_01_00.txt",
            "HuGaDB_v1_walking_01_00.txt",
            "HuGaDB_v1_walking_01_00",
        ),
        ("a.csv", "b.csv", "a"),
        // Only side words in the names: the folder names the subject.
        ("left.csv", "right.csv", "exported000"),
    ] {
        let v = discover(&[p(a), p(b)]).unwrap();
        assert_eq!(v[0].subject_id, want, "{a} {b}");
    }
    let opts = InputOptions {
        subject_id: Some("S9".into()),
        ..InputOptions::default()
    };
    let v = discover_with(&[p("a.csv"), p("b.csv")], &opts).unwrap();
    assert_eq!(v[0].subject_id, "S9");
    let e = discover_with(&[d.path().join("exported000")], &opts).unwrap_err();
    assert!(e.to_string().contains("--subject"), "{e}");
}

/// `setting = treadmill` turns the turn detection off (a walker on a belt cannot turn); the
/// same recordings overground have their turn's strides flagged.
#[test]
fn treadmill_setting_flags_no_stride_as_turning() {
    let c = ldh_sim::CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 40.0,
        seed: 3,
        turn: true,
        ..ldh_sim::CohortParams::default()
    };
    let s = c.simulate(0).unwrap();
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let leg = |l: &ldh_sim::SimLeg| -> LoadedLeg {
        Ok((
            l.recording.clone(),
            memory_report(&l.recording),
            "sim".into(),
        ))
    };
    let turning = |setting: Option<Setting>| -> usize {
        let input = SubjectInput {
            subject_id: "T".into(),
            setting,
            ..SubjectInput::default()
        };
        let r = Analysis::new(params.check().unwrap()).pair(&input, leg(&s.left), leg(&s.right));
        assert_eq!(r.setting, setting);
        r.legs()
            .iter()
            .map(|(_, l)| {
                let l = l.as_ref().unwrap();
                l.strides
                    .iter()
                    .filter(|x| x.reason.contains("turning"))
                    .count()
            })
            .sum()
    };
    assert!(turning(None) >= 2, "the simulated turn is found overground");
    assert_eq!(turning(Some(Setting::Overground)), turning(None));
    assert_eq!(turning(Some(Setting::Treadmill)), 0);
    assert_eq!(params.for_treadmill().strides.turn_deg, 180.0);
    params.for_treadmill().check().unwrap();
}
