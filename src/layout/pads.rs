use core::f64::consts::PI;

use geo::Coord;

/// Which way a pad lies from its sensor's centre line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PadSide {
    /// Towards smaller `s` (arm A's pad).
    Below,
    /// Towards larger `s` (arm B's pad).
    Above,
}

/// Distance along `s` from a sensor's centre line to the near edge of each of its pads (mm).
///
/// The pads sit in line with the arms when they can (straight leads), never closer together
/// than `pad_gap`, and never so far out that they come within `pad_gap` of the neighbouring
/// sensor's pads (BSN) or of each other round the back of the tube (UAN):
/// `t = max(gap/2, min(s_s/2, t_max))` with `t_max = π·r_o/k − gap/2 − P`, `k` the sensor
/// count. If even `gap/2` is too far out, the pads collide, which the clearance rule reports.
pub(crate) fn pad_offset_mm(
    sensor_arc_mm: f64,
    pad_gap_mm: f64,
    pad_size_mm: f64,
    outer_radius_mm: f64,
    sensor_count: u32,
) -> f64 {
    let room_mm = PI * outer_radius_mm / f64::from(sensor_count.max(1));
    let max_mm = room_mm - pad_gap_mm / 2.0 - pad_size_mm;
    (sensor_arc_mm / 2.0).min(max_mm).max(pad_gap_mm / 2.0)
}

/// The terminal of a pad, where its lead arrives: the pad's distal corner nearest the sensor's
/// centre line.
pub(crate) fn pad_terminal(
    pad_x_mm: f64,
    centre_s_mm: f64,
    offset_mm: f64,
    side: PadSide,
) -> Coord {
    let s_mm = match side {
        PadSide::Below => centre_s_mm - offset_mm,
        PadSide::Above => centre_s_mm + offset_mm,
    };
    Coord {
        x: pad_x_mm,
        y: s_mm,
    }
}

/// A square spiral of `turns` turns at `pitch_mm`, one continuous centre line from `terminal`
/// (a distal corner of its `2·turns·pitch` square) inwards to the centre.
///
/// Built outwards from the centre with legs of `p, p, 2p, 2p, …, 2n·p` turning left (+x, +s,
/// −x, −s, …), which ends at the square's corner `(−n·p, −n·p)`; then reversed so the pad starts
/// where its lead ends, and mirrored in `s` for a pad below its sensor so the terminal is the
/// corner nearest the sensor.
pub(crate) fn square_spiral(
    terminal: Coord,
    pitch_mm: f64,
    turns: u32,
    side: PadSide,
) -> Vec<Coord> {
    let n = f64::from(turns);
    let mirror = match side {
        PadSide::Above => 1.0,
        PadSide::Below => -1.0,
    };
    // Centre of the square, so that the local corner (−n·p, −n·p) lands on the terminal.
    let centre = Coord {
        x: terminal.x + n * pitch_mm,
        y: terminal.y + mirror * n * pitch_mm,
    };
    let directions = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
    let (mut u, mut v) = (0.0_f64, 0.0_f64);
    let mut points = vec![centre];
    for leg in 0..4 * turns as usize {
        let length_mm = (leg / 2 + 1) as f64 * pitch_mm;
        let (du, dv) = directions[leg % 4];
        u += du * length_mm;
        v += dv * length_mm;
        points.push(Coord {
            x: centre.x + u,
            y: centre.y + mirror * v,
        });
    }
    // The last corner is computed; pin it to the terminal exactly so the lead meets the pad.
    if let Some(last) = points.last_mut() {
        *last = terminal;
    }
    points.reverse();
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn spiral_starts_at_terminal_and_fills_its_square() {
        let t = Coord { x: 10.0, y: 0.2 };
        for side in [PadSide::Above, PadSide::Below] {
            let pts = square_spiral(t, 0.1, 4, side);
            assert_eq!(pts[0], t);
            assert_eq!(pts.len(), 17);
            let xs: Vec<f64> = pts.iter().map(|p| p.x).collect();
            let ss: Vec<f64> = pts.iter().map(|p| p.y).collect();
            let min = |v: &[f64]| v.iter().cloned().fold(f64::INFINITY, f64::min);
            let max = |v: &[f64]| v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            assert_relative_eq!(min(&xs), 10.0, epsilon = 1e-12);
            assert_relative_eq!(max(&xs), 10.8, epsilon = 1e-12);
            match side {
                PadSide::Above => {
                    assert_relative_eq!(min(&ss), 0.2, epsilon = 1e-12);
                    assert_relative_eq!(max(&ss), 1.0, epsilon = 1e-12);
                }
                PadSide::Below => {
                    assert_relative_eq!(min(&ss), -0.6, epsilon = 1e-12);
                    assert_relative_eq!(max(&ss), 0.2, epsilon = 1e-12);
                }
            }
            // Every leg is axis-aligned: the laser path is a square spiral.
            for w in pts.windows(2) {
                assert!(w[0].x == w[1].x || (w[0].y - w[1].y).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn pad_offset_follows_arms_within_room() {
        // UAN Joint A: pads in line with the arms.
        assert_relative_eq!(pad_offset_mm(0.4, 0.3, 0.8, 1.24, 1), 0.2);
        // Arms closer than the gap: pads pushed apart to gap/2.
        assert_relative_eq!(pad_offset_mm(0.1, 0.3, 0.8, 1.24, 1), 0.15);
        // BSN Joint C: pulled in so both sensors' pads fit round the tube.
        let t = pad_offset_mm(2.13, 0.3, 0.8, 0.8, 2);
        assert_relative_eq!(t, PI * 0.8 / 2.0 - 0.15 - 0.8, epsilon = 1e-12);
    }
}
