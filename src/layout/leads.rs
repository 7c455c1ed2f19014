use geo::Coord;

/// A lead from an arm's end to its pad's terminal: straight along `x` when they line up,
/// otherwise a square jog halfway along the lead.
pub(crate) fn lead(arm_end: Coord, terminal: Coord) -> Vec<Coord> {
    if (arm_end.y - terminal.y).abs() <= 1e-12 {
        return vec![arm_end, terminal];
    }
    let jog_x_mm = (arm_end.x + terminal.x) / 2.0;
    vec![
        arm_end,
        Coord {
            x: jog_x_mm,
            y: arm_end.y,
        },
        Coord {
            x: jog_x_mm,
            y: terminal.y,
        },
        terminal,
    ]
}
