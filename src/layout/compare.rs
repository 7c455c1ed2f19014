use geo::{Coord, LineString};

use super::{Layout, Notch, Trace};

impl Layout {
    /// How far apart two layouts are: the largest difference of any number or vertex coordinate
    /// (mm), or `Err` naming the first structural difference (name, counts, levels, sides,
    /// sensors, pieces, vertex counts). Used to check that a drawing read back is the layout
    /// that was drawn.
    ///
    /// # Errors
    /// A message naming what differs in structure.
    pub fn max_difference_mm(&self, other: &Layout) -> Result<f64, String> {
        if self.name != other.name {
            return Err(format!("name {:?} vs {:?}", self.name, other.name));
        }
        let mut worst = [
            (self.outer_radius_mm, other.outer_radius_mm),
            (self.circumference_mm, other.circumference_mm),
            (self.seam_s_mm, other.seam_s_mm),
            (self.trace_width_mm, other.trace_width_mm),
            (self.kerf_mm, other.kerf_mm),
            (self.length_mm, other.length_mm),
        ]
        .iter()
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
        let count = |what: &str, a: usize, b: usize| {
            if a == b {
                Ok(())
            } else {
                Err(format!("{what}: {a} vs {b}"))
            }
        };
        count("notches", self.notches.len(), other.notches.len())?;
        for (i, (a, b)) in self.notches.iter().zip(&other.notches).enumerate() {
            worst = worst.max(notch_difference(a, b).map_err(|e| format!("notch {i}: {e}"))?);
        }
        for (what, a, b) in [
            ("sensors", &self.sensors, &other.sensors),
            ("leads", &self.leads, &other.leads),
            ("pads", &self.pads, &other.pads),
        ] {
            count(what, a.len(), b.len())?;
            for (i, (ta, tb)) in a.iter().zip(b).enumerate() {
                worst =
                    worst.max(trace_difference(ta, tb).map_err(|e| format!("{what}[{i}]: {e}"))?);
            }
        }
        count("parting pieces", self.parting.len(), other.parting.len())?;
        for (a, b) in self.parting.iter().zip(&other.parting) {
            worst = worst.max(line_difference(&a.0, &b.0)?);
        }
        Ok(worst)
    }
}

fn notch_difference(a: &Notch, b: &Notch) -> Result<f64, String> {
    if (a.level, a.side) != (b.level, b.side) {
        return Err(format!(
            "level/side {:?} vs {:?}",
            (a.level, a.side),
            (b.level, b.side)
        ));
    }
    if a.outline.len() != b.outline.len() {
        return Err(format!("pieces {} vs {}", a.outline.len(), b.outline.len()));
    }
    a.outline
        .iter()
        .zip(&b.outline)
        .map(|(p, q)| line_difference(&p.exterior().0, &q.exterior().0))
        .try_fold(0.0_f64, |w, d| d.map(|d| w.max(d)))
}

fn trace_difference(a: &Trace, b: &Trace) -> Result<f64, String> {
    if a.sensor != b.sensor {
        return Err(format!("sensor {} vs {}", a.sensor, b.sensor));
    }
    if a.pieces.len() != b.pieces.len() {
        return Err(format!("pieces {} vs {}", a.pieces.len(), b.pieces.len()));
    }
    a.pieces
        .iter()
        .zip(&b.pieces)
        .map(|(p, q): (&LineString<f64>, &LineString<f64>)| line_difference(&p.0, &q.0))
        .try_fold(0.0_f64, |w, d| d.map(|d| w.max(d)))
}

fn line_difference(a: &[Coord], b: &[Coord]) -> Result<f64, String> {
    if a.len() != b.len() {
        return Err(format!("vertices {} vs {}", a.len(), b.len()));
    }
    Ok(a.iter()
        .zip(b)
        .map(|(p, q)| (p.x - q.x).abs().max((p.y - q.y).abs()))
        .fold(0.0, f64::max))
}
