//! The checked-in header is what cbindgen generates from the source today.
//! Regenerate with `DLW_BLESS=1 cargo test -p dlw-estimator-ffi --test header`.

use std::path::Path;

#[test]
fn checked_in_header_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen generates the header")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = dir.join("include/dlw_estimator.h");
    if std::env::var_os("DLW_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("writing the header");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "{} is stale: regenerate it with DLW_BLESS=1 cargo test -p dlw-estimator-ffi --test header",
        path.display()
    );
    for name in [
        "typedef struct DlwEstimator DlwEstimator;",
        "dlw_estimator_from_toml(const char *config_toml, char *error, size_t error_len)",
        "int dlw_estimator_step(DlwEstimator *e, double v1, double v2, double *angle_deg, uint32_t *flags)",
        "void dlw_estimator_reset(DlwEstimator *e)",
        "void dlw_estimator_free(DlwEstimator *e)",
        "typedef struct DlwRobotEstimator DlwRobotEstimator;",
        "DlwRobotEstimator *dlw_robot_estimator_from_toml(const char *config_toml,",
        "size_t dlw_robot_estimator_joints(const DlwRobotEstimator *e);",
        "size_t dlw_robot_estimator_sensors(const DlwRobotEstimator *e);",
        "double dlw_robot_estimator_condition_number(const DlwRobotEstimator *e);",
        "int dlw_robot_estimator_step(DlwRobotEstimator *e,",
        "int dlw_robot_estimator_tip(const DlwRobotEstimator *e,",
        "int dlw_robot_estimator_backbone(const DlwRobotEstimator *e,",
        "void dlw_robot_estimator_reset(DlwRobotEstimator *e);",
        "void dlw_robot_estimator_free(DlwRobotEstimator *e);",
        "#define DLW_FLAG_NOT_CONVERGED (1 << 6)",
        "#define DLW_MAX_SENSORS 16",
    ] {
        assert!(generated.contains(name), "the header lacks {name:?}:\n{generated}");
    }
}
