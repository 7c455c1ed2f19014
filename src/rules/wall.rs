//! The tube wall is thick enough for the sets that cut through it.

use super::Violation;
use crate::design::DesignFile;
use crate::process::ProcessSets;

/// Refuses a wall `r_o − r_i` thinner than the `min_wall_mm` of the set that cuts the notches
/// or the one that parts the joint off (each named once). Needs the design's process sets, so it
/// runs where they are resolved: by the laser planner ([`crate::toolpath::plan`]) for
/// `dlw program` and `dlw build`.
pub fn check_wall(file: &DesignFile, sets: &ProcessSets) -> Vec<Violation> {
    let (outer_mm, inner_mm) = (file.outer_radius_mm, file.inner_radius_mm);
    let wall_mm = outer_mm - inner_mm;
    let mut out = Vec::new();
    for (operation, set) in [("notches", &sets.notches), ("parting", &sets.parting)] {
        let named = out
            .iter()
            .any(|v| matches!(v, Violation::WallTooThin { set: s, .. } if *s == set.name));
        // A non-physical wall (r_i ≥ r_o) is the section rule's to report.
        if wall_mm > 0.0 && wall_mm < set.min_wall_mm && !named {
            out.push(Violation::WallTooThin {
                wall_mm,
                outer_mm,
                inner_mm,
                min_mm: set.min_wall_mm,
                set: set.name.clone(),
                operation,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::ProcessLibrary;

    fn sets() -> ProcessSets {
        ProcessLibrary::new(Vec::new())
            .resolve(&crate::design::ProcessChoice::default())
            .unwrap()
    }

    #[test]
    fn thin_walls_are_refused_with_the_numbers() {
        let text = include_str!("../../designs/joint-c.toml");
        let mut file = DesignFile::from_toml(text).unwrap();
        assert!(check_wall(&file, &sets()).is_empty(), "0.19 mm passes");
        file.inner_radius_mm = 0.78;
        let v = check_wall(&file, &sets());
        assert_eq!(v.len(), 1, "notches and parting share the set: named once");
        let msg = v[0].to_string();
        assert!(
            msg.contains("r_o − r_i = 0.0200 mm")
                && msg.contains("min_wall_mm = 0.1 mm")
                && msg.contains("\"notches\""),
            "{msg}"
        );
        let mut own = sets();
        own.notches.min_wall_mm = 0.01;
        own.parting.name = "parting".into();
        let v = check_wall(&file, &own);
        assert_eq!(v.len(), 1);
        assert!(v[0].to_string().contains("(parting)"), "{}", v[0]);
        // r_i ≥ r_o is the section rule's business.
        file.inner_radius_mm = 0.9;
        assert!(check_wall(&file, &sets()).is_empty());
    }
}
