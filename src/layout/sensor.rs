use geo::Coord;

use super::notches::notch_centre_s_mm;
use super::stations::Stations;

/// Arc-length centre of sensor `j`: sensor 0 (plane `+y_s`) at `s = 0`, BSN sensor 1 (plane
/// `−y_s`) at `s = π·r_o`, i.e. where the other notch side is.
pub(crate) fn sensor_centre_s_mm(sensor: usize, outer_radius_mm: f64) -> f64 {
    // Sensor 0 straddles φ = 0 and sensor 1 straddles φ = π: the opposite of notch side numbering.
    notch_centre_s_mm(1 - sensor.min(1), outer_radius_mm)
}

/// The U-trace of one sensor, unwrapped: arm A at `s_c − s_s/2` from the arm end down to the
/// bridge, the bridge across to `s_c + s_s/2`, and arm B back up to the arm end.
pub(crate) fn u_trace(centre_s_mm: f64, sensor_arc_mm: f64, stations: &Stations) -> Vec<Coord> {
    let (a_mm, b_mm) = arm_s_mm(centre_s_mm, sensor_arc_mm);
    vec![
        Coord {
            x: stations.arm_end_x_mm,
            y: a_mm,
        },
        Coord {
            x: stations.bridge_x_mm,
            y: a_mm,
        },
        Coord {
            x: stations.bridge_x_mm,
            y: b_mm,
        },
        Coord {
            x: stations.arm_end_x_mm,
            y: b_mm,
        },
    ]
}

/// Arc-length positions of arms A and B of a sensor centred at `centre_s_mm`.
pub(crate) fn arm_s_mm(centre_s_mm: f64, sensor_arc_mm: f64) -> (f64, f64) {
    (
        centre_s_mm - sensor_arc_mm / 2.0,
        centre_s_mm + sensor_arc_mm / 2.0,
    )
}
