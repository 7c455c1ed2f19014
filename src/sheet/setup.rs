//! The operator's setup sheet (Markdown): laser safety, stock and mandrel, fixturing, zeroing against the
//! drawing's frame, the parameter sets and times, and the steps after the laser.

use crate::machine::{format_number, MachineProfile, SettleMode};
use crate::toolpath::{
    estimate, format_duration, Feature, OperationKind, OperationTime, Plan, TraceKind,
};

/// Steel rod diameters the sheet picks a mandrel from (mm): common ground-rod and gauge-wire
/// sizes, including the paper's 1.2 mm and 1.5 mm.
pub const MANDREL_SIZES_MM: [f64; 14] = [
    0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0,
];

/// Least diametral clearance a mandrel must leave in the tube's bore (mm), so the tube slides
/// over it.
pub const MANDREL_CLEARANCE_MM: f64 = 0.01;

/// The mandrel for a bore of `inner_diameter_mm`: the largest size in [`MANDREL_SIZES_MM`] that
/// leaves at least [`MANDREL_CLEARANCE_MM`]; `None` when even the smallest does not fit.
///
/// This gives the paper's choices: 1.2 mm steel in the 1.6 mm OD tube (bore 1.22 mm) and
/// 1.5 mm in the 2.5 mm OD tube (bore 1.75 mm).
pub fn mandrel_mm(inner_diameter_mm: f64) -> Option<f64> {
    MANDREL_SIZES_MM
        .iter()
        .rev()
        .copied()
        .find(|d| inner_diameter_mm - d >= MANDREL_CLEARANCE_MM - 1e-12)
}

/// What the sheet needs besides the plan.
#[derive(Debug, Clone, Copy)]
pub struct SheetContext<'a> {
    /// The machine profile the program was written for.
    pub profile: &'a MachineProfile,
    /// The program's file name, as the operator will load it.
    pub program_file: &'a str,
}

/// Writes the setup sheet for `plan`.
pub fn setup_sheet(plan: &Plan, ctx: &SheetContext<'_>) -> String {
    let profile = ctx.profile;
    let times = estimate(plan, profile);
    let travel = Travel::of(plan, profile);
    let sections = [
        heading(plan, ctx, &times),
        stock_and_mandrel(plan, profile, &travel),
        fixturing(profile, &travel),
        zeroing(plan, profile, &travel),
        parameter_sets(plan, profile, &times, &travel),
        run(plan, profile),
        after_the_laser(plan),
    ];
    let mut s = String::new();
    for line in sections.iter().flatten() {
        s.push_str(line);
        s.push('\n');
    }
    s
}

/// Where the program goes along the tube, and the stock it needs for that.
struct Travel {
    /// The program's least and greatest linear coordinate (mm).
    x_min_mm: f64,
    x_max_mm: f64,
    /// Centre of the parting cut (mm).
    cut_x_mm: f64,
    /// Stock left beyond the program's reach, before the collet (mm).
    spare_mm: f64,
    /// The stock tube's length, rounded up to a whole mm: reach, spare and collet grip (mm).
    stock_len_mm: f64,
}

impl Travel {
    fn of(plan: &Plan, profile: &MachineProfile) -> Self {
        let moves = plan.moves();
        let x_max_mm = moves
            .iter()
            .flat_map(|m| [m.from.x_mm, m.to.x_mm])
            .fold(f64::NEG_INFINITY, f64::max);
        let x_min_mm = moves
            .iter()
            .flat_map(|m| [m.from.x_mm, m.to.x_mm])
            .fold(f64::INFINITY, f64::min);
        let spare_mm = 5.0;
        Self {
            x_min_mm,
            x_max_mm,
            cut_x_mm: plan.joint_length_mm + plan.kerf_mm / 2.0,
            spare_mm,
            stock_len_mm: (x_max_mm + spare_mm + profile.fixture.collet_grip_mm).ceil(),
        }
    }
}

/// The title, what the program is for and where it came from, the operations in order with
/// the estimated time, and the laser safety lines.
fn heading(plan: &Plan, ctx: &SheetContext<'_>, times: &[OperationTime]) -> Vec<String> {
    let profile = ctx.profile;
    let total: f64 = times.iter().map(|t| t.total_s()).sum();
    let mut w = vec![
        format!("# Setup sheet: {}", plan.design_name),
        String::new(),
        format!(
            "Program `{}` for the **{}** ({} post; profile {}). Design checksum `{}` — the program header must show the same.",
            ctx.program_file,
            profile.name,
            crate::post::post_for(profile.dialect).name(),
            profile.source,
            plan.design_checksum
        ),
    ];
    if let Some(p) = &plan.provenance {
        w.push(p.markdown());
    }
    w.push(format!(
        "One fixturing runs everything: the sensor (set `{}`), then the notches (set `{}`), then the parting cut (set `{}`). Estimated time {}.",
        set_name(plan, OperationKind::Sensor),
        set_name(plan, OperationKind::Notches),
        set_name(plan, OperationKind::Parting),
        format_duration(total)
    ));
    w.push(String::new());
    w.extend(super::safety_lines(plan));
    w
}

/// Section 1: the stock tube, its length, and the mandrel inside it.
fn stock_and_mandrel(plan: &Plan, profile: &MachineProfile, travel: &Travel) -> Vec<String> {
    let xl = profile.axes.linear;
    let od = 2.0 * plan.outer_radius_mm;
    let id = 2.0 * plan.inner_radius_mm;
    let wall = plan.outer_radius_mm - plan.inner_radius_mm;
    vec![
        "## 1. Stock tube and mandrel".into(),
        String::new(),
        "| item | what to use |".into(),
        "|---|---|".into(),
        format!(
            "| stock tube | polyimide, OD {} mm (r_o = {} mm), ID {} mm (r_i = {} mm), wall {} mm |",
            format_number(od),
            format_number(plan.outer_radius_mm),
            format_number(id),
            format_number(plan.inner_radius_mm),
            format_number(wall)
        ),
        format!(
            "| stock length | at least {} mm: the program reaches {xl}{}, plus {} mm spare, plus {} mm in the collet |",
            format_number(travel.stock_len_mm),
            format_number((travel.x_max_mm * 1e3).round() / 1e3),
            format_number(travel.spare_mm),
            format_number(profile.fixture.collet_grip_mm)
        ),
        format!("| mandrel | {} |", mandrel_line(od, id)),
        format!(
            "| mandrel length | at least {} mm: from the free end to the end of the collet |",
            format_number(travel.stock_len_mm)
        ),
        String::new(),
    ]
}

/// Section 2: mandrel, glue, collet and support jig.
fn fixturing(profile: &MachineProfile, travel: &Travel) -> Vec<String> {
    let xl = profile.axes.linear;
    vec![
        "## 2. Fixturing".into(),
        String::new(),
        "1. Slide the mandrel into the tube until it is flush with the tube's free end: the whole joint must sit on steel while it is cut.".into(),
        format!(
            "2. **Glue end = collet end.** Fix the mandrel with one small drop of cyanoacrylate at the collet end only, beyond {xl}{} (the stock side of the parting cut is scrap). Never glue the free end: after parting, the joint must slide off the mandrel.",
            format_number(((travel.cut_x_mm + 2.0) * 10.0).ceil() / 10.0)
        ),
        format!(
            "3. **Collet end:** clamp the glued end in the rotary stage's collet ({} mm of stock in the collet; in the paper, the right end).",
            format_number(profile.fixture.collet_grip_mm)
        ),
        "4. **Free end:** rest the free (distal) end in the support jig (in the paper, a 3D-printed jig at the left end); it must turn freely.".into(),
        String::new(),
    ]
}

/// Section 3: zeroing the linear, rotary and focus axes against the drawing's frame.
fn zeroing(plan: &Plan, profile: &MachineProfile, travel: &Travel) -> Vec<String> {
    let (xl, al, zl) = (profile.axes.linear, profile.axes.rotary, profile.axes.focus);
    let units = profile.axes.rotary_units.symbol();
    let bsn = plan
        .operations
        .iter()
        .flat_map(|o| o.paths.iter())
        .any(|p| matches!(p.feature, Feature::Notch { side: 1, .. }));
    vec![
        "## 3. Zeroing against the drawing's frame".into(),
        String::new(),
        format!(
            "The program's {xl} is the drawing's x and its {al} is s/r_o in {units}, so the program overlays the DXF exactly."
        ),
        String::new(),
        format!(
            "- **{xl}0 at the tube's free end face** (the distal end, x = 0 on the drawing); {xl} grows towards the collet. The program stays within {xl}{} … {xl}{} (profile travel {} … {} mm).",
            format_number((travel.x_min_mm * 1e3).round() / 1e3),
            format_number((travel.x_max_mm * 1e3).round() / 1e3),
            format_number(profile.limits.x_min_mm),
            format_number(profile.limits.x_max_mm)
        ),
        if bsn {
            format!(
                "- **{al}0 at s = 0**: on a fresh tube any orientation will do; the line under the beam at {al}0 becomes s = 0, the centre line of sensor 1. This is a BSN joint: its notch pairs are centred at {al}0 and {al}180 (s = 0 and s = π·r_o), sensor 1's arms straddle the {al}0 notches and sensor 2's the {al}180 notches, and the two backbones run along {al}90 and {al}270 (s = ±π·r_o/2)."
            )
        } else {
            format!(
                "- **{al}0 at s = 0**: on a fresh tube any orientation will do; the line under the beam at {al}0 becomes s = 0, the centre line of sensor 1 and of the backbone (this is a UAN joint). The notches are centred at {al}180 (s = π·r_o)."
            )
        },
        format!(
            "- **Sense of {al}:** once per machine, jog {al} from 0 to +10 {units}: the beam must now sit on the +s side of the {al}0 line (s grows upwards in the drawing). If it sits on the −s side the stage turns the other way and the sensor and pads would come out mirrored; reverse the axis in the controller first."
        ),
        format!(
            "- **{zl}: focus on the top of the tube** and make that {zl}{}: the rotation axis is at {zl}{} and the surface r_o = {} mm above it. The program moves {zl} there itself.",
            crate::post::fixed(plan.surface_z_mm, 4),
            format_number(profile.focus.z_axis_mm),
            format_number(plan.outer_radius_mm)
        ),
        String::new(),
    ]
}

/// Section 4: each operation's parameter set and estimated times, what the program leaves to
/// the operator, and how the cuts sit.
fn parameter_sets(
    plan: &Plan,
    profile: &MachineProfile,
    times: &[OperationTime],
    travel: &Travel,
) -> Vec<String> {
    let xl = profile.axes.linear;
    let total: f64 = times.iter().map(|t| t.total_s()).sum();
    let mut w = vec![
        "## 4. Parameter sets and estimated times".into(),
        String::new(),
        "| operation | set | wavelength | power | scan speed | pulse frequency | pulse width | passes | Z step | paths | beam-on time | rapids | total |".into(),
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|".into(),
    ];
    for (op, t) in plan.operations.iter().zip(times) {
        let p = &op.process;
        w.push(format!(
            "| {} | `{}` | {} nm | {} mW | {} mm/s | {} kHz | {} fs | {} | {} mm | {} | {} | {} | {} |",
            op.kind.name(),
            p.name,
            format_number(p.wavelength_nm),
            format_number(p.power_mw),
            format_number(p.scan_speed_mm_s),
            format_number(p.pulse_frequency_khz),
            format_number(p.pulse_width_fs),
            p.repetitions,
            format_number(p.z_step_or_zero_mm()),
            op.paths.len(),
            format_duration(t.beam_s),
            format_duration(t.rapid_s),
            format_duration(t.total_s())
        ));
    }
    w.push(String::new());
    w.push(format!(
        "Times: beam-on moves at the set's surface speed, rapids at the profile's speed limits without acceleration (a lower bound){}; total {}.",
        if times.iter().any(|t| t.settle_s > 0.0) {
            ", and the settle dwell"
        } else {
            ""
        },
        format_duration(total)
    ));
    w.extend(set_by_hand(profile));
    w.push(format!(
        "Cuts: notch outlines are offset inward by half the kerf ({} mm) and start from a lead-in inside the notch; the parting cut runs all the way round at {xl}{} ({} mm kerf), leaving part length {} mm beside bending length L = {} mm (the notched, bending section lies within the part, between the distal margin and the leads and pads).",
        format_number(plan.kerf_mm / 2.0),
        crate::post::fixed(travel.cut_x_mm, 4),
        format_number(plan.kerf_mm),
        format_number(plan.joint_length_mm),
        format_number(plan.bending_length_mm)
    ));
    w.push(String::new());
    w
}

/// The line telling the operator which laser parameters the program does not command, if any.
fn set_by_hand(profile: &MachineProfile) -> Option<String> {
    let l = &profile.laser;
    let by_hand: Vec<&str> = [
        (&l.wavelength, "wavelength"),
        (&l.pulse_frequency, "pulse frequency"),
        (&l.pulse_width, "pulse width"),
    ]
    .iter()
    .filter(|(t, _)| t.is_empty())
    .map(|(_, n)| *n)
    .collect();
    (!by_hand.is_empty()).then(|| {
        format!(
            "The program does not command the {}: set {} on the source to the table's values before each operation.",
            by_hand.join(", "),
            if by_hand.len() == 1 { "it" } else { "them" }
        )
    })
}

/// Section 5: the dry run, the run and where it waits for the source, taking the part off.
fn run(plan: &Plan, profile: &MachineProfile) -> Vec<String> {
    let mut w = vec![
        "## 5. Run".into(),
        String::new(),
        "1. Dry-run the program with the beam gate disabled and watch the tube and jig: nothing may touch the objective.".into(),
        "2. Run it. Do not touch the tube between operations: the sensor and notches are aligned because they are made in one setup.".into(),
    ];
    let settle_before: Vec<&str> = profile
        .settle
        .waits_before(&plan.operations, |op| &op.process)
        .iter()
        .map(|op| op.kind.name())
        .collect();
    if !settle_before.is_empty() {
        let how = match profile.settle.mode {
            SettleMode::OptionalStop => " Turn the controller's optional-stop switch on before the run: the program then pauses there; check the source's pulse frequency and width, then resume.".to_string(),
            SettleMode::Stop => " The program pauses there: check the source's pulse frequency and width, then resume.".to_string(),
            _ => String::new(),
        };
        w.push(format!(
            "   Before the {} the program sets the laser and waits for the source to settle at its new pulse frequency and width: {} (machine profile, `[settle]`).{how}",
            settle_before.join(", "),
            profile.settle.describe()
        ));
    }
    w.push(
        "3. After the parting cut, slide the joint off the mandrel towards the free end.".into(),
    );
    w.push(String::new());
    w
}

/// Section 6: the checklist after the laser, from the pads to the tendon.
fn after_the_laser(plan: &Plan) -> Vec<String> {
    let pads = plan
        .operations
        .iter()
        .filter(|o| o.kind == OperationKind::Sensor)
        .flat_map(|o| o.paths.iter())
        .map(|p| match &p.feature {
            Feature::Written { parts, .. } => {
                parts.iter().filter(|k| **k == TraceKind::Pad).count()
            }
            _ => 0,
        })
        .sum::<usize>();
    vec![
        "## 6. After the laser".into(),
        String::new(),
        format!(
            "- [ ] Protect the contact pads: a small amount of conductive silver epoxy (MG Chemicals 8331D) on each of the {pads} pads; cure overnight."
        ),
        "- [ ] Parylene-C: coat the whole joint by vacuum deposition, 8 g of parylene (Labcoater PDS 2010) for about 5 µm.".into(),
        "- [ ] Sand the parylene off the protected pads with a small file.".into(),
        "- [ ] PCB assembly: attach the pads to the PCB's pads with more silver epoxy, aligned in the 3D-printed jig; dry overnight; then add hot-melt adhesive for mechanical strength.".into(),
        "- [ ] Tendon: fix the nylon tendon, 0.28 mm diameter (OmniFlex 8 lb), to the joint's distal end.".into(),
    ]
}

fn set_name(plan: &Plan, kind: OperationKind) -> String {
    plan.operations
        .iter()
        .find(|o| o.kind == kind)
        .map_or_else(|| "-".into(), |o| o.process.name.clone())
}

fn mandrel_line(od: f64, id: f64) -> String {
    let paper = [(1.6, 1.2), (2.5, 1.5)]
        .iter()
        .find(|(tube, _)| (od - tube).abs() <= 0.05)
        .map(|(tube, rod)| (*tube, *rod));
    match (mandrel_mm(id), paper) {
        (Some(d), Some((tube, rod))) if (d - rod).abs() < 1e-9 => format!(
            "{} mm machine-steel rod, as the paper used in the {} mm OD tube ({} mm clearance in the {} mm bore)",
            format_number(d),
            format_number(tube),
            format_number(id - d),
            format_number(id)
        ),
        (Some(d), _) => format!(
            "{} mm steel rod: the largest common size ({} mm) that leaves at least {} mm in the {} mm bore (the paper used 1.2 mm in its 1.6 mm OD tube and 1.5 mm in its 2.5 mm OD tube). If it binds, take the next size down.",
            format_number(d),
            MANDREL_SIZES_MM.map(format_number).join(", "),
            format_number(MANDREL_CLEARANCE_MM),
            format_number(id)
        ),
        (None, _) => format!(
            "no common rod fits the {} mm bore: use a steel wire at most {} mm thick, or cut without a mandrel at reduced stiffness",
            format_number(id),
            format_number(id - MANDREL_CLEARANCE_MM)
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mandrels_are_the_papers_for_its_tubes() {
        // Joint B/C/D: 1.6 mm OD, r_i = 0.61 → bore 1.22 mm; Joint A: 2.48 mm OD, bore 1.75 mm.
        assert_eq!(mandrel_mm(1.22), Some(1.2));
        assert_eq!(mandrel_mm(1.75), Some(1.5));
        assert_eq!(mandrel_mm(1.2), Some(1.0));
        assert_eq!(mandrel_mm(0.2), None);
        assert!(mandrel_line(1.6, 1.22).starts_with("1.2 mm machine-steel rod, as the paper"));
        assert!(mandrel_line(2.48, 1.75).starts_with("1.5 mm machine-steel rod, as the paper"));
        assert!(mandrel_line(3.2, 2.6).starts_with("2.5 mm steel rod: the largest common size"));
    }
}
