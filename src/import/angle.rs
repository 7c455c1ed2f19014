//! The bending angle from the tracker's tip tool: the angle between the tool's z axis (what a
//! 5-DOF Aurora sensor reports) and the axis at rest (the mean over the still start), measured
//! in the bending plane, the plane through the rest axis that holds most of the deviation
//! (found from the data: the principal direction of the deviations). With a reference tool on
//! the base, the tip's axis is taken in the reference tool's frame, so that motion of the whole
//! setup cancels.

use super::tracker::ToolFrame;

/// Why no angle could be found.
#[derive(Debug, thiserror::Error)]
pub enum AngleError {
    /// Too few frames with the tool at the start.
    #[error("the tracker log has {found} frames with the tool in its first {rest_frames}; the rest axis needs at least {min}")]
    NoRest {
        /// Frames with the tool seen in the rest window.
        found: usize,
        /// The rest window (frames).
        rest_frames: usize,
        /// Needed.
        min: usize,
    },
    /// The rest window runs past the end of the log.
    #[error("--rest-s {rest_s} runs past the tracker log, whose frames span {span_s:.3} s: the rest window must lie inside the log")]
    RestPastLog {
        /// The rest window (s).
        rest_s: f64,
        /// The log's span (s).
        span_s: f64,
    },
    /// The rest window is not still.
    #[error("--rest-s {rest_s}: the tip is not still over the rest window: its axis spreads {spread_deg:.2}° RMS about its mean there (still means at most {MAX_REST_SPREAD_DEG}°); the log is still for the first {still_s:.1} s only: pass --rest-s {still_s:.1} or less")]
    NotStill {
        /// The rest window (s).
        rest_s: f64,
        /// The spread over it (°, RMS).
        spread_deg: f64,
        /// How long the still start is (s).
        still_s: f64,
    },
    /// The joint never leaves its rest axis.
    #[error(
        "the tip never bends away from its rest axis by more than {max_deg:.3}°: no bending plane"
    )]
    NoBending {
        /// The largest deviation (°).
        max_deg: f64,
    },
}

/// The fewest frames the rest axis is averaged over.
pub const MIN_REST_FRAMES: usize = 10;
/// The largest RMS spread (°) of the tip's axis about its mean over the rest window: about 1.5
/// times NDI's stated 0.30° RMS orientation accuracy of a 5-DOF Aurora sensor, so a still tip
/// passes, and a joint that moves by more shifts every angle by about what it moved.
pub const MAX_REST_SPREAD_DEG: f64 = 0.5;
/// The smallest bending (°) from which a plane is found.
pub const MIN_BENDING_DEG: f64 = 1.0;

/// Per frame: the in-plane angle (°, `None` where the tool is missing), and the out-of-plane
/// component's RMS and maximum (°).
#[derive(Debug, Clone, PartialEq)]
pub struct BendingAngles {
    /// In-plane angle per frame (°), positive toward the plane's principal direction.
    pub angle_deg: Vec<Option<f64>>,
    /// RMS of the out-of-plane angle over the frames with the tool (°).
    pub out_of_plane_rms_deg: f64,
    /// Largest |out-of-plane angle| (°).
    pub out_of_plane_max_deg: f64,
    /// The in-plane range (°), for the 5 % warning.
    pub in_plane_range_deg: f64,
}

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: V3) -> V3 {
    let n = dot(a, a).sqrt();
    if n > 0.0 {
        scale(a, 1.0 / n)
    } else {
        a
    }
}

/// `v` (in the tracker's frame) in the frame of a tool with orientation `q` (scalar first):
/// `Rᵀ·v`.
fn into_frame(q: [f64; 4], v: V3) -> V3 {
    let [w, x, y, z] = q;
    let r = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    [
        r[0][0] * v[0] + r[1][0] * v[1] + r[2][0] * v[2],
        r[0][1] * v[0] + r[1][1] * v[1] + r[2][1] * v[2],
        r[0][2] * v[0] + r[1][2] * v[1] + r[2][2] * v[2],
    ]
}

/// The RMS angle (°) of unit vectors about their mean direction, from their sum `sum` and
/// count `n`: the mean squared chord to the mean direction is `2 − 2·|sum|/n`, and a chord is
/// the angle (in radians) to within 1 % below 14°.
fn spread_deg(sum: V3, n: usize) -> f64 {
    let m = dot(sum, sum).sqrt() / n as f64;
    (2.0 - 2.0 * m).max(0.0).sqrt().to_degrees()
}

/// The still start: the tracker time (s) of the first frame whose axis lies more than
/// [`MAX_REST_SPREAD_DEG`] from the mean of the frames before it (0 if one of the first
/// [`MIN_REST_FRAMES`] does).
fn still_start_s(axes: &[Option<V3>], tau_s: &[f64]) -> f64 {
    let (mut sum, mut n) = ([0.0; 3], 0usize);
    let limit = MAX_REST_SPREAD_DEG.to_radians().cos();
    for (a, &tau) in axes.iter().zip(tau_s) {
        let Some(a) = a else { continue };
        if n > 0 && dot(*a, unit(sum)) < limit {
            return if n >= MIN_REST_FRAMES { tau } else { 0.0 };
        }
        sum = [sum[0] + a[0], sum[1] + a[1], sum[2] + a[2]];
        n += 1;
    }
    tau_s.last().copied().unwrap_or(0.0)
}

/// The bending angles of `tip`, relative to `reference` when given (a frame counts only when
/// both tools are seen), with the rest axis averaged over the frames of the first `rest_s`
/// seconds of tracker time `tau_s`. The rest window must lie inside the log and be still: the
/// tip's axis within [`MAX_REST_SPREAD_DEG`] RMS of its mean.
///
/// # Errors
/// [`AngleError`].
pub fn bending_angles(
    tip: &[Option<ToolFrame>],
    reference: Option<&[Option<ToolFrame>]>,
    tau_s: &[f64],
    rest_s: f64,
) -> Result<BendingAngles, AngleError> {
    let span_s = tau_s.last().copied().unwrap_or(0.0);
    if rest_s.is_nan() || rest_s > span_s {
        return Err(AngleError::RestPastLog { rest_s, span_s });
    }
    let rest_frames = tau_s.partition_point(|&t| t < rest_s);
    let axes: Vec<Option<V3>> = tip
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let z = t.as_ref()?.z_axis();
            match reference {
                None => Some(z),
                Some(r) => Some(into_frame(r.get(i).copied().flatten()?.quaternion, z)),
            }
        })
        .collect();
    let rest: Vec<V3> = axes.iter().take(rest_frames).flatten().copied().collect();
    if rest.len() < MIN_REST_FRAMES {
        return Err(AngleError::NoRest {
            found: rest.len(),
            rest_frames,
            min: MIN_REST_FRAMES,
        });
    }
    let sum = rest
        .iter()
        .fold([0.0; 3], |a, v| [a[0] + v[0], a[1] + v[1], a[2] + v[2]]);
    let spread = spread_deg(sum, rest.len());
    if spread > MAX_REST_SPREAD_DEG {
        return Err(AngleError::NotStill {
            rest_s,
            spread_deg: spread,
            still_s: still_start_s(&axes, tau_s),
        });
    }
    let r = unit(sum);
    // An orthonormal pair (u, v) across the rest axis, and the deviations in it.
    let helper = if r[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = unit(sub(helper, scale(r, dot(helper, r))));
    let v = cross(r, u);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    let mut max_dev = 0.0_f64;
    for a in axes.iter().flatten() {
        let (x, y) = (dot(*a, u), dot(*a, v));
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
        max_dev = max_dev.max((x * x + y * y).sqrt().asin().to_degrees());
    }
    if max_dev.is_nan() || max_dev <= MIN_BENDING_DEG {
        return Err(AngleError::NoBending { max_deg: max_dev });
    }
    // The principal direction of the 2×2 scatter [[sxx, sxy], [sxy, syy]].
    let phi = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let p = unit([
        u[0] * phi.cos() + v[0] * phi.sin(),
        u[1] * phi.cos() + v[1] * phi.sin(),
        u[2] * phi.cos() + v[2] * phi.sin(),
    ]);
    let q = cross(r, p);
    let mut angle_deg = Vec::with_capacity(axes.len());
    let (mut ss, mut n, mut out_max) = (0.0, 0usize, 0.0_f64);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for a in &axes {
        angle_deg.push(a.map(|a| {
            let in_plane = dot(a, p).atan2(dot(a, r)).to_degrees();
            let out = dot(a, q).clamp(-1.0, 1.0).asin().to_degrees();
            ss += out * out;
            n += 1;
            out_max = out_max.max(out.abs());
            lo = lo.min(in_plane);
            hi = hi.max(in_plane);
            in_plane
        }));
    }
    Ok(BendingAngles {
        angle_deg,
        out_of_plane_rms_deg: (ss / n.max(1) as f64).sqrt(),
        out_of_plane_max_deg: out_max,
        in_plane_range_deg: hi - lo,
    })
}
