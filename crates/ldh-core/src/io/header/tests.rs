use super::*;
use crate::io::format::{AccUnit, ColumnRef, GyroUnit, TimeUnit};

fn h(s: &str) -> Vec<String> {
    s.split(',').map(String::from).collect()
}

#[test]
fn names_alternatives_indices_prefix_and_blocks() {
    let mut f = FormatSpec::default();
    let hd = h("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z");
    let c = resolve(&f, &hd).unwrap();
    assert_eq!((c.time, c.acc, c.gyro), (Some(0), [1, 2, 3], [4, 5, 6]));
    f.acc.columns[0] = ColumnRef::AnyOf(vec!["ax".into(), "ACC_X".into()]);
    f.gyro.columns[2] = ColumnRef::Index(2);
    let c = resolve(&f, &hd).unwrap();
    assert_eq!((c.acc[0], c.gyro[2]), (1, 1));
    let mut p = FormatSpec::default();
    p.sensor.prefix = "RS_".into();
    let hd2 = h("RF_acc_x,RS_time_s,RS_acc_x,RS_acc_y,RS_acc_z,RS_gyro_x,RS_gyro_y,RS_gyro_z");
    assert_eq!(resolve(&p, &hd2).unwrap().acc, [2, 3, 4]);
    let hd3 =
        h("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z");
    let d = resolve(&FormatSpec::default(), &hd3).unwrap_err();
    assert_eq!(
        d,
        Unresolved::Duplicate {
            column: "acc_x".into(),
            positions: vec![2, 8]
        }
    );
    let mut b = FormatSpec::default();
    b.sensor.block = Some(2);
    b.time.column = Some(ColumnRef::Index(1));
    let c = resolve(&b, &hd3).unwrap();
    assert_eq!((c.acc, c.gyro), ([7, 8, 9], [10, 11, 12]));
}

#[test]
fn missing_columns_name_only_what_is_missing_and_the_closest_names() {
    let hd = h("time_s,AccX,acc_y,acc_z,gyro_x,gyro_y,Gyr_Z,Status");
    let Unresolved::Missing(m) = resolve(&FormatSpec::default(), &hd).unwrap_err() else {
        panic!("missing expected")
    };
    let (names, hint) = describe_missing(&m, &hd, &FormatSpec::default());
    assert_eq!(names, vec!["acc_x", "gyro_z"]);
    assert!(hint.contains("acc_x → AccX;"), "{hint}");
    assert!(hint.ends_with("gyro_z → Gyr_Z"), "{hint}");
    assert!(!hint.contains("Status"), "{hint}");
}

#[test]
fn unit_suffixed_names_give_the_units() {
    let hd = h("time_ms,acc_x_mps2,acc_y_mps2,acc_z_mps2,gyro_x_rad_s,gyro_y_rad_s,gyro_z_rad_s");
    let f = unit_suffixed(&FormatSpec::default(), &hd).unwrap();
    assert_eq!(f.time.unit, TimeUnit::Milliseconds);
    assert_eq!((f.acc.unit, f.gyro.unit), (AccUnit::Mps2, GyroUnit::Rps));
    assert!(resolve(&f, &hd).is_ok());
    let plain = h("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z");
    assert!(unit_suffixed(&FormatSpec::default(), &plain).is_none());
    let half = h("time_s,acc_x_g,acc_y_g,gyro_x_dps,gyro_y_dps,gyro_z_dps");
    assert!(unit_suffixed(&FormatSpec::default(), &half).is_none());
    let xs = FormatSpec::builtin("xsens-mtmanager").unwrap();
    assert!(unit_suffixed(&xs, &hd).is_none());
}
