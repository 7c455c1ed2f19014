//! The candidate space: the Cartesian product of the varied axes, each candidate named by one
//! index (mixed radix, the last axis fastest), so the space is never held in memory.

use dlw_geometry::NotchStyle;

use crate::design::DesignFile;

use super::catalogue::Tube;

/// Written joint lengths are rounded to 1/this of a mm (1 pm).
const LENGTH_ROUNDING_PER_MM: f64 = 1e9;

/// A candidate's parameters (everything the explorer varies).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Index of the tube in [`Grid::tubes`].
    pub tube: usize,
    /// Outer radius `r_o` (mm).
    pub outer_radius_mm: f64,
    /// Inner radius `r_i` (mm).
    pub inner_radius_mm: f64,
    /// Notch style (sensor count 1 for UAN, 2 for BSN).
    pub style: NotchStyle,
    /// Notch arc `s_n` (mm).
    pub notch_arc_mm: f64,
    /// Sensor arc `s_s` (mm).
    pub sensor_arc_mm: f64,
    /// Notch count `N`.
    pub notch_count: u32,
    /// Notch width `h` (mm).
    pub notch_width_mm: f64,
    /// Notch spacing `c` (mm).
    pub notch_spacing_mm: f64,
}

impl Params {
    /// The joint length the notch pattern needs, `N·h + (N−1)·c` (mm): a written design states
    /// it so the length rule holds by construction.
    pub fn joint_length_mm(&self) -> f64 {
        let n = f64::from(self.notch_count);
        let exact = n * self.notch_width_mm + (n - 1.0) * self.notch_spacing_mm;
        // Rounded to 1 pm, far inside the length rule's 1 µm, so files read `6.8`, not
        // `6.800000000000001`.
        (exact * LENGTH_ROUNDING_PER_MM).round() / LENGTH_ROUNDING_PER_MM
    }

    /// The base design with these parameters, named `name`.
    pub fn apply(&self, base: &DesignFile, name: String) -> DesignFile {
        let mut file = base.clone();
        file.name = name;
        file.outer_radius_mm = self.outer_radius_mm;
        file.inner_radius_mm = self.inner_radius_mm;
        file.style = self.style;
        file.notch_arc_mm = self.notch_arc_mm;
        file.sensor_arc_mm = self.sensor_arc_mm;
        file.notch_count = self.notch_count;
        file.notch_width_mm = self.notch_width_mm;
        file.notch_spacing_mm = self.notch_spacing_mm;
        file.joint_length_mm = self.joint_length_mm();
        file
    }
}

/// The axes' values.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Tube sizes.
    pub tubes: Vec<Tube>,
    /// Notch styles.
    pub styles: Vec<NotchStyle>,
    /// `s_n` values (mm).
    pub notch_arcs_mm: Vec<f64>,
    /// `s_s` values (mm).
    pub sensor_arcs_mm: Vec<f64>,
    /// `N` values.
    pub notch_counts: Vec<u32>,
    /// `h` values (mm).
    pub notch_widths_mm: Vec<f64>,
    /// `c` values (mm).
    pub notch_spacings_mm: Vec<f64>,
}

impl Grid {
    /// The axis lengths, slowest first.
    fn radices(&self) -> [usize; 7] {
        [
            self.tubes.len(),
            self.styles.len(),
            self.notch_arcs_mm.len(),
            self.sensor_arcs_mm.len(),
            self.notch_counts.len(),
            self.notch_widths_mm.len(),
            self.notch_spacings_mm.len(),
        ]
    }

    /// Candidates in the grid, or `None` past `u64`.
    pub fn len(&self) -> Option<u64> {
        self.radices()
            .iter()
            .try_fold(1u64, |acc, &r| acc.checked_mul(r as u64))
    }

    /// Whether the grid is empty (an axis without values).
    pub fn is_empty(&self) -> bool {
        self.len() == Some(0)
    }

    /// The parameters of candidate `index` (`index < len()`).
    pub fn params(&self, index: u64) -> Params {
        let mut digits = [0usize; 7];
        let mut rest = index;
        let radices = self.radices();
        for (d, &r) in digits.iter_mut().zip(radices.iter()).rev() {
            *d = (rest % r as u64) as usize;
            rest /= r as u64;
        }
        let tube = &self.tubes[digits[0]];
        Params {
            tube: digits[0],
            outer_radius_mm: tube.outer_radius_mm,
            inner_radius_mm: tube.inner_radius_mm,
            style: self.styles[digits[1]],
            notch_arc_mm: self.notch_arcs_mm[digits[2]],
            sensor_arc_mm: self.sensor_arcs_mm[digits[3]],
            notch_count: self.notch_counts[digits[4]],
            notch_width_mm: self.notch_widths_mm[digits[5]],
            notch_spacing_mm: self.notch_spacings_mm[digits[6]],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_index_names_a_distinct_candidate() {
        let tube = |id: &str, ro| Tube {
            id: id.into(),
            outer_radius_mm: ro,
            inner_radius_mm: ro / 2.0,
            source: String::new(),
        };
        let g = Grid {
            tubes: vec![tube("a", 1.0), tube("b", 2.0)],
            styles: vec![NotchStyle::Uan],
            notch_arcs_mm: vec![1.0, 2.0, 3.0],
            sensor_arcs_mm: vec![0.4],
            notch_counts: vec![5, 6],
            notch_widths_mm: vec![0.5],
            notch_spacings_mm: vec![0.4, 0.5],
        };
        assert_eq!(g.len(), Some(24));
        let all: Vec<Params> = (0..24).map(|i| g.params(i)).collect();
        for (i, a) in all.iter().enumerate() {
            assert!(all[..i].iter().all(|b| b != a), "{i} repeats");
        }
        assert_eq!(g.params(0).notch_spacing_mm, 0.4);
        assert_eq!(g.params(1).notch_spacing_mm, 0.5);
        assert_eq!(g.params(23).tube, 1);
    }
}
