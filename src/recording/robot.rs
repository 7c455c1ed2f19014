//! A robot's recording (issue 34 §1): the same folder as a joint's, `rig.toml` and `data.csv`,
//! with numbered columns. For `N` joints and `M` sensors (sensors in `dlw inspect ROBOT --json`'s
//! `"sensors"` order) the header is fixed:
//!
//! ```text
//! time_s,stroke1_mm,…,strokeN_mm,angle1_deg,…,angleN_deg,v1_V,…,vM_V[,tip_x_mm,tip_y_mm,tip_z_mm][,tracker_valid]
//! ```
//!
//! - `rig.toml` is a joint recording's [`Rig`], with `M` entries in `divider_ohm` (at most
//!   [`MAX_RECORDING_SENSORS`]);
//! - `angleK_deg` is joint `K`'s measured angle; the angle columns are empty in every row (no
//!   per-joint tracker) or in none;
//! - `tip_*` is a tracker's tip position in the robot's base frame (`docs/robot-runtime.md`);
//! - `tracker_valid` marks rows whose tracked angles and tip no analysis may use.
//!
//! `N` is read from the header (the `strokeK_mm` columns), `M` from the rig. Every check of a
//! joint's recording applies, through the same bounded reader and the same field parser: the
//! header, each row's fields, finite numbers within their column's limit, increasing time, no
//! voltage at a rail, the sample rate. The joint's reader is not changed: a robot recording is
//! read only by the robot commands, which know they read one from their other input (a robot
//! file or a robot estimator config).

use std::path::Path;

use crate::fixed::push_fixed;
use crate::output::write_folder_atomic;

use super::{
    check_sample_rate, folder_files, parse_field, read_text, refuse_unmeasured, Measured,
    RecordingError, Rig, DATA_FILE, RIG_FILE, VALID_COLUMN_SUFFIX,
};

/// The most joints a robot recording holds (the runtime's `MAX_JOINTS`).
pub const MAX_RECORDING_JOINTS: usize = dlw_estimator::MAX_JOINTS;
/// The most sensors a robot recording holds (the runtime's `MAX_SENSORS`).
pub const MAX_RECORDING_SENSORS: usize = dlw_estimator::MAX_SENSORS;

/// What the tracker's tip columns add to the header.
pub const TIP_COLUMNS_SUFFIX: &str = ",tip_x_mm,tip_y_mm,tip_z_mm";

/// The samples of a robot recording, one vector per column.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RobotSamples {
    /// `time_s` (s).
    pub time_s: Vec<f64>,
    /// `strokeK_mm`, one vector per joint (mm).
    pub stroke_mm: Vec<Vec<f64>>,
    /// `angleK_deg`, one vector per joint (°); every vector empty for a recording without
    /// per-joint angles.
    pub angle_deg: Vec<Vec<f64>>,
    /// `vK_V`, one vector per sensor (V).
    pub volts: Vec<Vec<f64>>,
    /// `tip_x_mm`, `tip_y_mm`, `tip_z_mm` when the recording has them (mm, base frame).
    pub tip_mm: Option<[Vec<f64>; 3]>,
    /// `tracker_valid`: empty when the column is absent (every row valid).
    pub tracker_valid: Vec<bool>,
}

impl RobotSamples {
    /// Empty columns for `joints` joints and `sensors` sensors, with or without the tip.
    pub fn new(joints: usize, sensors: usize, tip: bool) -> Self {
        Self {
            time_s: Vec::new(),
            stroke_mm: vec![Vec::new(); joints],
            angle_deg: vec![Vec::new(); joints],
            volts: vec![Vec::new(); sensors],
            tip_mm: tip.then(Default::default),
            tracker_valid: Vec::new(),
        }
    }

    /// Rows.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// Joints `N`.
    pub fn joints(&self) -> usize {
        self.stroke_mm.len()
    }

    /// Sensors `M`.
    pub fn sensors(&self) -> usize {
        self.volts.len()
    }

    /// Whether the recording has every joint's measured angle.
    pub fn has_joint_angles(&self) -> bool {
        self.angle_deg.iter().all(|a| a.len() == self.len())
    }

    /// Whether row `i`'s tracked values (angles, tip) may be used.
    pub fn tracker_valid_at(&self, i: usize) -> bool {
        self.tracker_valid.get(i).copied().unwrap_or(true)
    }
}

/// A robot recording: rig and samples.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotRecording {
    /// `rig.toml`, with one divider per sensor.
    pub rig: Rig,
    /// `data.csv`.
    pub samples: RobotSamples,
}

/// The header for `joints` joints and `sensors` sensors, with the tip columns if `tip`, without
/// `tracker_valid`.
pub fn robot_header(joints: usize, sensors: usize, tip: bool) -> String {
    let mut h = String::from("time_s");
    for k in 1..=joints {
        h.push_str(&format!(",stroke{k}_mm"));
    }
    for k in 1..=joints {
        h.push_str(&format!(",angle{k}_deg"));
    }
    for k in 1..=sensors {
        h.push_str(&format!(",v{k}_V"));
    }
    if tip {
        h.push_str(TIP_COLUMNS_SUFFIX);
    }
    h
}

impl RobotRecording {
    /// Reads and checks a robot recording folder.
    ///
    /// # Errors
    /// [`RecordingError`] naming the file, the line and the value.
    pub fn read(dir: &Path) -> Result<Self, RecordingError> {
        let rig_path = dir.join(RIG_FILE);
        let rig_text = read_text(&rig_path, crate::limits::MAX_TEXT_INPUT_BYTES)?;
        let rig: Rig = toml::from_str(&rig_text).map_err(|e| RecordingError::RigParse {
            path: rig_path.clone(),
            message: crate::limits::parser_message(&e),
        })?;
        rig.check_with(&rig_path, MAX_RECORDING_SENSORS, "1 to 16 sensors")?;
        let data_path = dir.join(DATA_FILE);
        let text = read_text(&data_path, crate::limits::MAX_RECORDING_BYTES)?;
        let samples = parse_robot_data(&text, &rig, &data_path)?;
        check_sample_rate(&rig, &samples.time_s, &rig_path, &data_path)?;
        Ok(Self { rig, samples })
    }

    /// [`read`](Self::read)s a robot recording a model will be fitted to, and refuses it when
    /// a column was not measured throughout ([`check_measured`](Self::check_measured)).
    ///
    /// # Errors
    /// Those of [`read`](Self::read) and of [`check_measured`](Self::check_measured).
    pub fn read_measured(dir: &Path) -> Result<Self, RecordingError> {
        let rec = Self::read(dir)?;
        rec.check_measured(dir)?;
        Ok(rec)
    }

    /// Refuses a robot recording one of whose columns was not measured throughout
    /// ([`Recording::check_measured`]): a joint's angle or the tip (on the rows the tracker
    /// marks valid) or a voltage clipped by the instrument's range, or a joint's angle holding
    /// one value while its own stroke moves. A voltage is not checked for a hold: the joints its
    /// sensor does not sit on may be the ones moving. `dir` is the folder read, for the message.
    ///
    /// Refuses it too when the tracker's clock is off the DAQ's: every joint's angle late
    /// against the strokes and the voltages by one delay ([`super::clock::check_robot`]).
    ///
    /// [`Recording::check_measured`]: super::Recording::check_measured
    ///
    /// # Errors
    /// [`RecordingError::Clipped`], [`RecordingError::Frozen`] and
    /// [`RecordingError::TrackerDelay`].
    pub fn check_measured(&self, dir: &Path) -> Result<(), RecordingError> {
        let s = &self.samples;
        let valid: Vec<usize> = (0..s.time_s.len())
            .filter(|&i| s.tracker_valid_at(i))
            .collect();
        fn tracked<'a>(
            name: String,
            v: &[f64],
            valid: &[usize],
            stroke: Option<&'a [f64]>,
        ) -> Measured<'a> {
            Measured {
                name,
                values: valid.iter().map(|&i| v[i]).collect(),
                rows: valid.to_vec(),
                stroke,
            }
        }
        let mut columns = Vec::new();
        for (k, a) in s
            .angle_deg
            .iter()
            .enumerate()
            .filter(|(_, a)| !a.is_empty())
        {
            let stroke = s.stroke_mm.get(k).map(Vec::as_slice);
            columns.push(tracked(format!("angle{}_deg", k + 1), a, &valid, stroke));
        }
        for (axis, v) in ["x", "y", "z"].iter().zip(s.tip_mm.iter().flatten()) {
            columns.push(tracked(format!("tip_{axis}_mm"), v, &valid, None));
        }
        for (k, v) in s.volts.iter().enumerate() {
            columns.push(Measured {
                name: format!("v{}_V", k + 1),
                values: v.clone(),
                rows: (0..v.len()).collect(),
                stroke: None,
            });
        }
        refuse_unmeasured(dir, &s.time_s, columns)?;
        super::clock::check_robot(self, dir)
    }

    /// Checks the recording by its reader's rules on what [`RobotRecording::write`] would put in
    /// the folder (the rig, `data.csv` as written, parsed back, and the sample rate), without
    /// writing it: an importer's last check before it writes.
    ///
    /// # Errors
    /// [`RecordingError`] naming `rig.toml` or `data.csv`, the line and the value.
    pub fn check(&self) -> Result<(), RecordingError> {
        let (rig_path, data_path) = (Path::new(RIG_FILE), Path::new(DATA_FILE));
        self.rig
            .check_with(rig_path, MAX_RECORDING_SENSORS, "1 to 16 sensors")?;
        let text = String::from_utf8_lossy(&self.csv_bytes()).into_owned();
        let samples = parse_robot_data(&text, &self.rig, data_path)?;
        check_sample_rate(&self.rig, &samples.time_s, rig_path, data_path)
    }

    /// Writes the recording as folder `dest`, atomically; an existing non-empty `dest` is
    /// replaced only with `replace`.
    ///
    /// # Errors
    /// [`RecordingError::Exists`], or an I/O error naming the path; `dest` is then untouched.
    pub fn write(&self, dest: &Path, replace: bool) -> Result<(), RecordingError> {
        let files = folder_files(dest, replace, &self.rig, self.csv_bytes())?;
        write_folder_atomic(dest, &files)?;
        Ok(())
    }

    /// `data.csv` as bytes: time, stroke, voltage and tip to 6 decimals, angles to 4.
    pub fn csv_bytes(&self) -> Vec<u8> {
        let s = &self.samples;
        let n = s.joints();
        let mut out = Vec::with_capacity(s.len() * (12 + 30 * n + 10 * s.sensors()) + 128);
        out.extend_from_slice(robot_header(n, s.sensors(), s.tip_mm.is_some()).as_bytes());
        let marked = !s.tracker_valid.is_empty();
        if marked {
            out.extend_from_slice(VALID_COLUMN_SUFFIX.as_bytes());
        }
        out.push(b'\n');
        let angles = s.has_joint_angles();
        for i in 0..s.len() {
            push_fixed(&mut out, s.time_s[i], 6);
            for c in &s.stroke_mm {
                out.push(b',');
                push_fixed(&mut out, c[i], 6);
            }
            for c in &s.angle_deg {
                out.push(b',');
                if angles {
                    push_fixed(&mut out, c[i], 4);
                }
            }
            for c in &s.volts {
                out.push(b',');
                push_fixed(&mut out, c[i], 6);
            }
            if let Some(tip) = &s.tip_mm {
                for c in tip {
                    out.push(b',');
                    push_fixed(&mut out, c[i], 6);
                }
            }
            if marked {
                out.extend_from_slice(if s.tracker_valid[i] { b",1" } else { b",0" });
            }
            out.push(b'\n');
        }
        out
    }
}

/// The header's shape: joints, and whether it has the tip and `tracker_valid` columns; `None`
/// when `first` is not a robot header for `sensors` sensors.
fn header_shape(first: &str, sensors: usize) -> Option<(usize, bool, bool)> {
    let joints = first
        .split(',')
        .skip(1)
        .take_while(|c| c.starts_with("stroke") && c.ends_with("_mm"))
        .count();
    if !(1..=MAX_RECORDING_JOINTS).contains(&joints) {
        return None;
    }
    let (rest, marked) = match first.strip_suffix(VALID_COLUMN_SUFFIX) {
        Some(r) => (r, true),
        None => (first, false),
    };
    [false, true]
        .into_iter()
        .find(|&tip| robot_header(joints, sensors, tip) == rest)
        .map(|tip| (joints, tip, marked))
}

fn parse_robot_data(text: &str, rig: &Rig, path: &Path) -> Result<RobotSamples, RecordingError> {
    let sensors = rig.divider_ohm.len();
    let mut lines = text.split('\n').enumerate();
    let first = lines.next().map_or("", |(_, l)| l.trim_end_matches('\r'));
    let Some((joints, tip, marked)) = header_shape(first, sensors) else {
        return Err(header_error(first, sensors, path));
    };
    let columns = Columns::new(first, joints, sensors, tip, marked);
    let mut samples = RobotSamples::new(joints, sensors, tip);
    let mut row = vec![0.0f64; columns.names.len()];
    let mut blank = None;
    let mut angles_empty: Option<(usize, bool)> = None;
    for (i, raw) in lines {
        let line = i + 1;
        let text = raw.trim_end_matches('\r');
        if text.is_empty() {
            blank.get_or_insert(line);
            continue;
        }
        if let Some(line) = blank {
            return Err(columns.fields_error(path, line, 0));
        }
        let empty = columns.read_row(text, line, &mut row, path)?;
        check_angles_alike(&mut angles_empty, line, empty, path)?;
        columns.push_row(&row, empty, line, rig, path, &mut samples)?;
    }
    if samples.is_empty() {
        return Err(RecordingError::NoRows {
            path: path.to_path_buf(),
        });
    }
    Ok(samples)
}

/// The error for a first line that is not a robot header: it names the header a robot of as
/// many joints as the line seems to have would need.
fn header_error(first: &str, sensors: usize, path: &Path) -> RecordingError {
    let joints = first
        .split(',')
        .filter(|c| c.starts_with("stroke"))
        .count()
        .max(1);
    RecordingError::Header {
        path: path.to_path_buf(),
        found: crate::limits::quote(first),
        expected: format!(
            "{}[{TIP_COLUMNS_SUFFIX}][{VALID_COLUMN_SUFFIX}]",
            robot_header(joints, sensors, false)
        ),
        sensors,
    }
}

/// Where each quantity sits in a robot data row, from its header.
struct Columns {
    /// The header line as read.
    header: String,
    /// The column names, in order.
    names: Vec<String>,
    joints: usize,
    sensors: usize,
    /// Whether the rows carry a `tracker_valid` column.
    marked: bool,
    angles_at: usize,
    volts_at: usize,
    tip_at: usize,
    valid_at: usize,
}

impl Columns {
    fn new(first: &str, joints: usize, sensors: usize, tip: bool, marked: bool) -> Self {
        let volts_at = 1 + 2 * joints;
        let tip_at = volts_at + sensors;
        Columns {
            header: first.to_string(),
            names: first.split(',').map(str::to_string).collect(),
            joints,
            sensors,
            marked,
            angles_at: 1 + joints,
            volts_at,
            tip_at,
            valid_at: tip_at + if tip { 3 } else { 0 },
        }
    }

    /// Line `line` has `found` fields where the header has more or fewer.
    fn fields_error(&self, path: &Path, line: usize, found: usize) -> RecordingError {
        RecordingError::Fields {
            path: path.to_path_buf(),
            line,
            found,
            expected: self.names.len(),
            header: self.header.clone(),
        }
    }

    /// Parses line `line` (`text`) into `row`; returns whether its angle columns are empty.
    fn read_row(
        &self,
        text: &str,
        line: usize,
        row: &mut [f64],
        path: &Path,
    ) -> Result<bool, RecordingError> {
        let (angles_at, volts_at, valid_at) = (self.angles_at, self.volts_at, self.valid_at);
        let mut n = 0;
        let mut empty_angles = 0;
        for field in text.split(',') {
            if n >= self.names.len() {
                n += 1;
                continue;
            }
            if (angles_at..volts_at).contains(&n) && field.is_empty() {
                empty_angles += 1;
            } else if self.marked && n == valid_at {
                row[n] = match field.trim() {
                    "1" => 1.0,
                    "0" => 0.0,
                    _ => {
                        return Err(RecordingError::Number {
                            path: path.to_path_buf(),
                            line,
                            column: "tracker_valid (must be 0 or 1)".to_string(),
                            text: crate::limits::quote(field),
                        })
                    }
                };
            } else {
                row[n] = parse_field(field, line, &self.names[n], path)?;
            }
            n += 1;
        }
        if n != self.names.len() {
            return Err(self.fields_error(path, line, n));
        }
        let joints = self.joints;
        if empty_angles != 0 && empty_angles != joints {
            return Err(RecordingError::Number {
                path: path.to_path_buf(),
                line,
                column: "angleK_deg (empty in every angle column, or in none)".to_string(),
                text: format!("{empty_angles} of {joints} empty"),
            });
        }
        Ok(empty_angles == joints)
    }

    /// Checks a parsed row's time and voltages and appends it to `samples`.
    fn push_row(
        &self,
        row: &[f64],
        empty: bool,
        line: usize,
        rig: &Rig,
        path: &Path,
        samples: &mut RobotSamples,
    ) -> Result<(), RecordingError> {
        if let Some(&previous_s) = samples.time_s.last() {
            if row[0] <= previous_s {
                return Err(RecordingError::TimeNotIncreasing {
                    path: path.to_path_buf(),
                    line,
                    time_s: row[0],
                    previous_s,
                });
            }
        }
        for c in 0..self.sensors {
            let volts = row[self.volts_at + c];
            if !(volts > 0.0 && volts < rig.supply_v) {
                return Err(RecordingError::Rail {
                    path: path.to_path_buf(),
                    line,
                    column: self.names[self.volts_at + c].clone(),
                    volts,
                    supply_v: rig.supply_v,
                });
            }
            samples.volts[c].push(volts);
        }
        samples.time_s.push(row[0]);
        for j in 0..self.joints {
            samples.stroke_mm[j].push(row[1 + j]);
            if !empty {
                samples.angle_deg[j].push(row[self.angles_at + j]);
            }
        }
        if let Some(t) = &mut samples.tip_mm {
            for (k, c) in t.iter_mut().enumerate() {
                c.push(row[self.tip_at + k]);
            }
        }
        if self.marked {
            samples.tracker_valid.push(row[self.valid_at] == 1.0);
        }
        Ok(())
    }
}

/// Every row must have its angles, or every row must have them empty: `angles_empty` holds the
/// first row's line and whether it had them empty.
fn check_angles_alike(
    angles_empty: &mut Option<(usize, bool)>,
    line: usize,
    empty: bool,
    path: &Path,
) -> Result<(), RecordingError> {
    match *angles_empty {
        None => *angles_empty = Some((line, empty)),
        Some((first_line, first)) if first != empty => {
            return Err(RecordingError::MixedAngle {
                path: path.to_path_buf(),
                line,
                found: if empty { "empty" } else { "a number" },
                first_line,
                first: if first {
                    "has it empty"
                } else {
                    "has a number"
                },
            });
        }
        Some(_) => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rig(sensors: usize) -> Rig {
        Rig {
            sample_hz: 500.0,
            supply_v: 5.0,
            divider_ohm: vec![99.6e3; sensors],
            notes: None,
            simulation: None,
            design: None,
            scenario: None,
            protocol: None,
            import: None,
        }
    }

    #[test]
    fn the_header_is_fixed_by_joints_sensors_and_the_tip() {
        assert_eq!(
            robot_header(2, 3, true),
            "time_s,stroke1_mm,stroke2_mm,angle1_deg,angle2_deg,v1_V,v2_V,v3_V,tip_x_mm,tip_y_mm,tip_z_mm"
        );
        assert_eq!(
            header_shape(&robot_header(2, 3, false), 3),
            Some((2, false, false))
        );
        let marked = format!("{}{VALID_COLUMN_SUFFIX}", robot_header(3, 4, true));
        assert_eq!(header_shape(&marked, 4), Some((3, true, true)));
        // Sensors must match the rig's dividers.
        assert_eq!(header_shape(&robot_header(2, 3, false), 2), None);
        // A joint recording's header is not a robot's.
        assert_eq!(header_shape("time_s,stroke_mm,angle_deg,v1_V", 1), None);
    }

    #[test]
    fn parses_good_data_and_names_bad_lines() {
        let path = Path::new("data.csv");
        let h = robot_header(2, 3, false);
        let good = format!("{h}\n0,0,0,0,0,1,1,1\n0.002,0.1,0.2,1,2,1.5,1.6,1.7\n");
        let s = parse_robot_data(&good, &rig(3), path).unwrap();
        assert_eq!((s.len(), s.joints(), s.sensors()), (2, 2, 3));
        assert_eq!(s.angle_deg[1], vec![0.0, 2.0]);
        assert_eq!(s.volts[2], vec![1.0, 1.7]);
        assert!(s.has_joint_angles() && s.tip_mm.is_none());
        let table = [
            (format!("{h}\n0,0,0,0,0,1,1\n"), "line 2: has 7 fields"),
            (format!("{h}\n0,0,0,0,0,1,1,1,1\n"), "line 2: has 9 fields"),
            (format!("{h}\n0,0,0,0,NaN,1,1,1\n"), "angle2_deg = NaN"),
            (format!("{h}\n0,0,0,0,400,1,1,1\n"), "angle2_deg = 4e2"),
            (format!("{h}\n0,0,x,0,0,1,1,1\n"), "stroke2_mm = \"x\""),
            (
                format!("{h}\n0,0,0,0,0,1,1,5\n"),
                "v3_V = 5 V is at or beyond a rail",
            ),
            (
                format!("{h}\n1,0,0,0,0,1,1,1\n1,0,0,0,0,1,1,1\n"),
                "does not increase",
            ),
            (format!("{h}\n0,0,0,,0,1,1,1\n"), "1 of 2 empty"),
            (
                format!("{h}\n0,0,0,,,1,1,1\n0.1,0,0,1,1,1,1,1\n"),
                "line 3: angle_deg is a number",
            ),
            (format!("{h}\n"), "no data rows"),
            (
                "time_s,stroke_mm,angle_deg,v1_V,v2_V,v3_V\n0,0,0,1,1,1\n".to_string(),
                "line 1",
            ),
        ];
        for (text, needle) in table {
            let err = parse_robot_data(&text, &rig(3), path)
                .unwrap_err()
                .to_string();
            assert!(err.contains(needle), "{text:?}: {err}");
        }
    }

    #[test]
    fn write_then_read_round_trips_with_tip_and_gaps() {
        let dir = tempfile::tempdir().unwrap();
        let dest = dir.path().join("rec");
        let mut samples = RobotSamples::new(2, 3, true);
        for i in 0..4 {
            let t = i as f64 * 0.002;
            samples.time_s.push(t);
            for j in 0..2 {
                samples.stroke_mm[j].push(0.125 * i as f64 + j as f64);
                samples.angle_deg[j].push(1.5 * i as f64 - j as f64);
            }
            for c in 0..3 {
                samples.volts[c].push(1.0 + 0.25 * (i + c) as f64);
            }
            let tip = samples.tip_mm.as_mut().unwrap();
            tip[0].push(0.5 * i as f64);
            tip[1].push(-0.25);
            tip[2].push(30.0 - i as f64);
            samples.tracker_valid.push(i != 2);
        }
        let rec = RobotRecording {
            rig: rig(3),
            samples,
        };
        rec.write(&dest, false).unwrap();
        assert_eq!(RobotRecording::read(&dest).unwrap(), rec);
        let text = std::fs::read_to_string(dest.join(DATA_FILE)).unwrap();
        assert!(text.starts_with(&format!(
            "{}{VALID_COLUMN_SUFFIX}\n",
            robot_header(2, 3, true)
        )));
        assert!(rec.write(&dest, false).is_err());
        // Without per-joint angles: empty fields, read back as empty columns.
        let mut bare = rec.clone();
        bare.samples.angle_deg = vec![Vec::new(); 2];
        bare.write(&dest, true).unwrap();
        let back = RobotRecording::read(&dest).unwrap();
        assert!(!back.samples.has_joint_angles());
        assert_eq!(back, bare);
        // Seventeen dividers are more than a recording holds.
        let mut many = rec.clone();
        many.rig.divider_ohm = vec![1e5; 17];
        many.write(&dest, true).unwrap();
        let err = RobotRecording::read(&dest).unwrap_err().to_string();
        assert!(err.contains("divider_ohm (entries) = 17"), "{err}");
    }
}
