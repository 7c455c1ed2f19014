//! The driver: walks a plan and writes a program through a [`Post`].

use super::{fixed, AxisWords, FeedMove, MachineState, Post, PostError};
use crate::machine::{format_number, LaserValues, MachineProfile, RepeatMode};
use crate::process::ProcessSet;
use crate::toolpath::{estimate, format_duration, Path, Plan, Point};

/// Writes the whole program for `plan` in `post`'s dialect.
///
/// # Errors
/// [`PostError::Unsupported`] when the profile asks for loops the post cannot write.
pub fn write_program(
    plan: &Plan,
    profile: &MachineProfile,
    post: &dyn Post,
) -> Result<String, PostError> {
    let mut w = Writer {
        post,
        profile,
        plan,
        out: Vec::new(),
        state: MachineState::default(),
        next_loop: 100,
        lin: post.linear_decimals(),
        rot: post.rotary_decimals(profile),
        per_rad: profile.axes.rotary_units.per_rad(),
    };
    for line in header_lines(plan, profile, post) {
        w.out.push(post.comment(&line));
    }
    w.out.extend(post.preamble(profile));
    w.beam_off(true);
    let z0 = w.q_lin(plan.surface_z_mm);
    let words = w.state.words_to(AxisWords {
        z: Some(z0),
        ..AxisWords::default()
    });
    w.out.push(post.rapid(profile, &words));
    let mut prev: Option<&ProcessSet> = None;
    for op in &plan.operations {
        w.operation(op, prev)?;
        prev = Some(&op.process);
    }
    w.beam_off(false);
    w.out.extend(post.postamble(profile));
    let mut text = w.out.join("\n");
    text.push('\n');
    Ok(text)
}

/// The header every program starts with, as plain lines (the post makes them comments):
/// design and checksum, machine, frame, kerf, the parameter table, estimated times, travel.
pub fn header_lines(plan: &Plan, profile: &MachineProfile, post: &dyn Post) -> Vec<String> {
    let units = profile.axes.rotary_units.symbol();
    let (x, a, z) = (profile.axes.linear, profile.axes.rotary, profile.axes.focus);
    let mut h = vec![
        format!("dlw laser program for design \"{}\"", plan.design_name),
        format!("design checksum {} (FNV-1a 64 of the design's canonical TOML)", plan.design_checksum),
        format!("machine profile {} ({}), {} post", profile.name, profile.source, post.name()),
        format!(
            "frame: {x} = drawing x in mm, 0 at the tube's free (distal) end; {a} = s/r_o in {units}, {a}0 at s = 0; r_o = {} mm",
            format_number(plan.outer_radius_mm)
        ),
        format!(
            "focus: {z}{} is the tube's surface ({z}{} on the rotation axis + r_o)",
            fixed(plan.surface_z_mm, 4),
            format_number(profile.focus.z_axis_mm)
        ),
        format!(
            "kerf {} mm: notch outlines offset inward by {} mm; parting cut centre at {x}{} so the part is {} mm long (part length; the bending length L = {} mm lies within it)",
            format_number(plan.kerf_mm),
            format_number(plan.kerf_mm / 2.0),
            fixed(plan.joint_length_mm + plan.kerf_mm / 2.0, 4),
            format_number(plan.joint_length_mm),
            format_number(plan.bending_length_mm)
        ),
        "parameter sets (paper Table II):".into(),
        format!(
            "{:<9} {:<10} {:>8} {:>9} {:>11} {:>10} {:>9} {:>7} {:>10}",
            "operation", "set", "wl nm", "power mW", "speed mm/s", "pulse kHz", "pulse fs", "passes", "Z step mm"
        ),
    ];
    // Where the layout came from, after the design's name and checksum (`--from-dxf` only).
    h.splice(
        2..2,
        plan.notes
            .iter()
            .cloned()
            .chain(plan.provenance.iter().flat_map(|p| p.lines())),
    );
    for op in &plan.operations {
        let p = &op.process;
        h.push(format!(
            "{:<9} {:<10} {:>8} {:>9} {:>11} {:>10} {:>9} {:>7} {:>10}",
            op.kind.name(),
            p.name,
            format_number(p.wavelength_nm),
            format_number(p.power_mw),
            format_number(p.scan_speed_mm_s),
            format_number(p.pulse_frequency_khz),
            format_number(p.pulse_width_fs),
            p.repetitions,
            format_number(p.z_step_or_zero_mm())
        ));
    }
    let times = estimate(plan, profile);
    let parts: Vec<String> = times
        .iter()
        .map(|t| format!("{} {}", t.kind.name(), format_duration(t.total_s())))
        .collect();
    let total: f64 = times.iter().map(|t| t.total_s()).sum();
    let settles: Vec<&str> = profile
        .settle
        .waits_before(&plan.operations, |op| &op.process)
        .iter()
        .map(|op| op.kind.name())
        .collect();
    if !settles.is_empty() {
        h.push(format!(
            "settle: {} after the laser is set, before {} (machine profile, table settle)",
            profile.settle.describe(),
            settles.join(", ")
        ));
    }
    h.push(format!(
        "estimated time: {}; total {}",
        parts.join(", "),
        format_duration(total)
    ));
    let travel: Vec<String> = plan
        .operations
        .iter()
        .zip(&plan.travel)
        .map(|(op, t)| {
            format!(
                "{} {:.2} ({:.2})",
                op.kind.name(),
                t.planned_mm,
                t.layout_order_mm
            )
        })
        .collect();
    h.push(format!(
        "rapid travel mm, planned (layout order): {}",
        travel.join(", ")
    ));
    let mut by_hand = Vec::new();
    let l = &profile.laser;
    for (t, what) in [
        (&l.wavelength, "wavelength"),
        (&l.pulse_frequency, "pulse frequency"),
        (&l.pulse_width, "pulse width"),
    ] {
        if t.is_empty() {
            by_hand.push(what);
        }
    }
    if !by_hand.is_empty() {
        h.push(format!(
            "not commanded by this program, set by hand per the table: {}",
            by_hand.join(", ")
        ));
    }
    h
}

struct Writer<'a> {
    post: &'a dyn Post,
    profile: &'a MachineProfile,
    plan: &'a Plan,
    out: Vec<String>,
    state: MachineState,
    next_loop: u32,
    lin: usize,
    rot: usize,
    per_rad: f64,
}

/// Where the focus goes at the start of a pass.
#[derive(Clone, Copy)]
enum PassZ {
    /// A fixed Z (mm).
    At(f64),
    /// The loop's focus variable, lowered by the step after the rapid.
    Variable(f64),
}

impl Writer<'_> {
    fn q_lin(&self, v: f64) -> f64 {
        fixed(v, self.lin).parse().unwrap_or(v)
    }

    fn q_rot(&self, a_rad: f64) -> f64 {
        let v = a_rad * self.per_rad;
        fixed(v, self.rot).parse().unwrap_or(v)
    }

    fn beam_off(&mut self, always: bool) {
        if self.state.beam_on || always {
            self.out
                .extend(self.profile.laser.beam_off.render(&self.values(None)));
            self.state.beam_on = false;
        }
    }

    fn beam_on(&mut self) {
        if !self.state.beam_on {
            self.out
                .extend(self.profile.laser.beam_on.render(&self.values(None)));
            self.state.beam_on = true;
        }
    }

    fn values(&self, set: Option<&ProcessSet>) -> LaserValues {
        LaserValues {
            power_mw: set.map_or(0.0, |s| s.power_mw),
            max_power_mw: self.profile.limits.max_power_mw,
            pulse_frequency_khz: set.map_or(0.0, |s| s.pulse_frequency_khz),
            pulse_width_fs: set.map_or(0.0, |s| s.pulse_width_fs),
            wavelength_nm: set.map_or(0.0, |s| s.wavelength_nm),
        }
    }

    fn set_laser(&mut self, set: &ProcessSet) {
        let v = self.values(Some(set));
        let l = &self.profile.laser;
        let lines =
            [&l.power, &l.pulse_frequency, &l.pulse_width, &l.wavelength].map(|t| t.render(&v));
        for (i, lines) in lines.iter().enumerate() {
            if !lines.is_empty() && self.state.laser_changed(i, lines) {
                self.out.extend(lines.iter().cloned());
            }
        }
    }

    fn operation(
        &mut self,
        op: &crate::toolpath::Operation,
        prev: Option<&ProcessSet>,
    ) -> Result<(), PostError> {
        let set = &op.process;
        self.out.push(String::new());
        self.out.push(self.post.comment(&format!(
            "operation {}: set {}, {} mW, {} mm/s, {} path(s), {} pass(es) each",
            op.kind.name(),
            set.name,
            format_number(set.power_mw),
            format_number(set.scan_speed_mm_s),
            op.paths.len(),
            set.repetitions
        )));
        self.beam_off(false);
        self.set_laser(set);
        if self.profile.settle.needed(prev, set) {
            self.out.extend(self.post.settle(&self.profile.settle));
        }
        let step = set.z_step_or_zero_mm();
        let reps = set.repetitions;
        let z_of = |k: u32| self.plan.surface_z_mm - f64::from(k) * step;
        for path in &op.paths {
            self.out.push(
                self.post
                    .comment(&format!("{}: {} pass(es)", path.feature, reps)),
            );
            let per_body: u32 = if path.reverse.is_some() { 2 } else { 1 };
            let count = reps / per_body;
            let wants_loop = self.profile.repetitions == RepeatMode::Loop && count >= 2;
            let loop_lines = if wants_loop {
                self.post.loop_begin(self.next_loop, count)
            } else {
                None
            };
            let z_var = if step > 0.0 && loop_lines.is_some() {
                self.post.z_variable_set(self.q_lin(z_of(0)))
            } else {
                None
            };
            match loop_lines {
                Some(_) if step > 0.0 && z_var.is_none() => {
                    return Err(self.unsupported("a Z step inside repeat loops"));
                }
                Some(lines) => {
                    let id = self.next_loop;
                    self.next_loop += 1;
                    self.out.extend(z_var.unwrap_or_default());
                    self.out.extend(lines);
                    self.state.forget_position();
                    for j in 0..per_body {
                        let z = if step > 0.0 {
                            PassZ::Variable(step)
                        } else {
                            PassZ::At(z_of(0))
                        };
                        self.pass(path, j, z, set.scan_speed_mm_s);
                    }
                    self.out.extend(self.post.loop_end(id));
                    if reps % per_body == 1 {
                        self.pass(
                            path,
                            reps - 1,
                            PassZ::At(z_of(reps - 1)),
                            set.scan_speed_mm_s,
                        );
                    }
                }
                None if wants_loop => return Err(self.unsupported("repetitions = \"loop\"")),
                None => {
                    for k in 0..reps {
                        self.pass(path, k, PassZ::At(z_of(k)), set.scan_speed_mm_s);
                    }
                }
            }
        }
        self.beam_off(false);
        Ok(())
    }

    fn unsupported(&self, what: &'static str) -> PostError {
        PostError::Unsupported {
            profile: self.profile.name.clone(),
            post: self.post.name(),
            what,
            instead: "set repetitions = \"unroll\" in the profile",
        }
    }

    /// One pass: beam off, rapid to the start (and the pass's focus), beam on, every move at
    /// the surface speed, beam off.
    fn pass(&mut self, path: &Path, k: u32, z: PassZ, speed_mm_s: f64) {
        let pts = path.pass(k);
        let Some(&first) = pts.first() else { return };
        self.beam_off(false);
        match z {
            PassZ::At(z_mm) => {
                let target = self.target(first, Some(z_mm));
                let words = self.state.words_to(target);
                if words != AxisWords::default() {
                    self.out.push(self.post.rapid(self.profile, &words));
                }
            }
            PassZ::Variable(step_mm) => {
                let target = self.target(first, None);
                let words = self.state.words_to(target);
                if words != AxisWords::default() {
                    self.out.push(self.post.rapid(self.profile, &words));
                }
                self.out
                    .extend(self.post.z_variable_rapid_and_step(self.profile, step_mm));
                self.state.z = None;
            }
        }
        self.beam_on();
        for p in &pts[1..] {
            self.feed(*p, speed_mm_s);
        }
        self.beam_off(false);
    }

    fn target(&self, p: Point, z_mm: Option<f64>) -> AxisWords {
        AxisWords {
            x: Some(self.q_lin(p.x_mm)),
            a: Some(self.q_rot(p.a_rad)),
            z: z_mm.map(|z| self.q_lin(z)),
        }
    }

    fn feed(&mut self, to: Point, speed_mm_s: f64) {
        let (Some(x0), Some(a0)) = (self.state.x, self.state.a) else {
            return;
        };
        let target = self.target(to, None);
        let dx_mm = (target.x.unwrap_or(x0) - x0).abs();
        let da_units = (target.a.unwrap_or(a0) - a0).abs();
        let d = dx_mm.hypot(self.plan.outer_radius_mm * da_units / self.per_rad);
        if d == 0.0 {
            return;
        }
        let words = self.state.words_to(target);
        let mv = FeedMove {
            words,
            dx_mm,
            da_units,
            seconds: d / speed_mm_s,
        };
        self.out.push(self.post.feed(self.profile, &mv));
    }
}
