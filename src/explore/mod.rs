//! `dlw explore`: from requirements to joints. A spec names a base design, the parameters to
//! vary, the sensing model, constraints and objectives; the explorer scores every candidate in
//! the grid, keeps those that meet every constraint and every design rule, and finds the Pareto
//! front of the objectives (`docs/explore.md`).
//!
//! The search is an object whose steps are methods, each testable alone:
//! 1. [`Exploration::load`]: read the spec, the base design and the tube catalogue into a
//!    [`Grid`] and a [`Model`];
//! 2. [`Exploration::screen`]: score every candidate with the geometry crate's mechanics and
//!    the sensing model, in parallel (rayon) and without allocating per candidate, and keep
//!    those that meet the spec's constraints;
//! 3. [`Exploration::check_rules`]: run the same design rules as `dlw build` (parameter,
//!    layout and clearance rules, and the wall rule against the cutting sets) on each survivor;
//! 4. [`Exploration::front`] and [`Exploration::best`]: the Pareto front and the best `K`.
//!
//! When nothing is feasible, [`Exploration::check_rules`] says which constraint binds.

mod catalogue;
mod evaluate;
mod grid;
mod pareto;
mod predict;
mod report;
mod spec;

use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::design::{DesignError, DesignFile};
use crate::process::{ProcessError, ProcessLibrary, ProcessSets};
use crate::rules::{self, RulesError, Violation};

/// The tube catalogue.
pub use catalogue::{Catalogue, Tube};
/// Scoring one candidate.
pub use evaluate::{evaluate, Constraint, DesignMetrics, Model};
/// The candidate space.
pub use grid::{Grid, Params};
/// The Pareto front.
pub use pareto::{dominates, front, front_with_ties, tied, TIE_RELATIVE};
/// The twin's predicted accuracy of a front candidate.
pub use predict::{Predicted, Predictor};
/// The output folder's files and the `--json` summary.
pub use report::{files, ExploreSummary, Files, Row};
/// The spec file.
pub use spec::{Axis, Constraints, Metric, Objectives, SpecError, SpecFile, Vary};
/// Limits on a spec's size.
pub use spec::{MAX_AXIS_VALUES, MAX_CANDIDATES};

/// Candidates scored per parallel task (and per progress update).
const CHUNK: u64 = 1 << 14;
/// Most survivors of the screen the design rules are run on: at about 1.2 ms each
/// (`docs/performance.md`), 10⁶ take 10 minutes on two cores, and they stay in memory.
pub const MAX_SURVIVORS: u64 = 1_000_000;

/// Why an exploration stopped.
#[derive(Debug, thiserror::Error)]
pub enum ExploreError {
    /// The spec or the catalogue.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// The base design could not be read.
    #[error(transparent)]
    Design(#[from] DesignError),
    /// The base design breaks a design rule.
    #[error("base design: {0}")]
    Base(#[from] RulesError),
    /// The base design's process sets.
    #[error(transparent)]
    Process(#[from] ProcessError),
    /// The grid is too large.
    #[error("the spec describes {count} candidates; at most {max} are allowed (narrow an axis or take a coarser step)")]
    TooMany {
        /// Candidates described (saturated at `u64::MAX`).
        count: u64,
        /// [`MAX_CANDIDATES`].
        max: u64,
    },
    /// Too many candidates meet the constraints to run the design rules on them all.
    #[error("{count} candidates meet the constraints; the design rules run on at most {max} (about 1.2 ms each): tighten a constraint or narrow an axis")]
    TooManySurvivors {
        /// Candidates meeting the constraints.
        count: u64,
        /// [`MAX_SURVIVORS`].
        max: u64,
    },
    /// Nothing meets every constraint and design rule.
    #[error("no candidate is feasible: {0}")]
    Infeasible(String),
    /// The twin that predicts accuracy could not be read.
    #[error("the twin of the paper's bench: {0}")]
    Twin(#[from] crate::reproduce::TwinError),
}

/// A scored candidate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    /// Its index in the grid.
    pub index: u64,
    /// Its parameters.
    pub params: Params,
    /// Its metrics.
    pub metrics: DesignMetrics,
}

/// What the screen found: the survivors and, for the infeasible message, per-constraint counts.
#[derive(Debug, Clone, Default)]
pub struct Screen {
    /// Candidates scored.
    pub evaluated: u64,
    /// Candidates whose section, joint or tendon the geometry refused.
    pub geometry_refused: u64,
    /// Candidates failing each constraint (by [`Constraint::ALL`] order).
    pub failing: [u64; 6],
    /// Candidates failing only that constraint.
    pub failing_only: [u64; 6],
    /// The best value of the constraint's quantity among those failing only it.
    pub best_failing_only: [Option<f64>; 6],
    /// The best value of the constraint's quantity over every candidate with a valid geometry.
    pub best_any: [Option<f64>; 6],
    /// Candidates meeting every constraint, in grid order (at most [`MAX_SURVIVORS`] kept).
    pub survivors: Vec<Candidate>,
    /// Candidates meeting every constraint, all counted.
    pub survivors_total: u64,
}

impl Screen {
    fn add(&mut self, index: u64, params: Params, scored: Option<(DesignMetrics, u8)>) {
        self.evaluated += 1;
        let Some((metrics, mask)) = scored else {
            self.geometry_refused += 1;
            return;
        };
        for (k, c) in Constraint::ALL.into_iter().enumerate() {
            let v = c.value(&metrics);
            self.best_any[k] = Some(self.best_any[k].map_or(v, |b| c.better(b, v)));
        }
        if mask == 0 {
            self.survivors_total += 1;
            if (self.survivors.len() as u64) < MAX_SURVIVORS {
                self.survivors.push(Candidate {
                    index,
                    params,
                    metrics,
                });
            }
            return;
        }
        for (k, c) in Constraint::ALL.into_iter().enumerate() {
            if mask & c.bit() == 0 {
                continue;
            }
            self.failing[k] += 1;
            if mask == c.bit() {
                self.failing_only[k] += 1;
                let v = c.value(&metrics);
                let best = &mut self.best_failing_only[k];
                *best = Some(best.map_or(v, |b| c.better(b, v)));
            }
        }
    }

    fn merge(mut self, other: Self) -> Self {
        self.evaluated += other.evaluated;
        self.geometry_refused += other.geometry_refused;
        for k in 0..6 {
            self.failing[k] += other.failing[k];
            self.failing_only[k] += other.failing_only[k];
            let c = Constraint::ALL[k];
            let better = |a: Option<f64>, b: Option<f64>| match (a, b) {
                (Some(a), Some(b)) => Some(c.better(a, b)),
                (a, b) => a.or(b),
            };
            self.best_failing_only[k] =
                better(self.best_failing_only[k], other.best_failing_only[k]);
            self.best_any[k] = better(self.best_any[k], other.best_any[k]);
        }
        self.survivors_total += other.survivors_total;
        self.survivors.extend(other.survivors);
        self.survivors.truncate(MAX_SURVIVORS as usize);
        self
    }
}

/// An exploration, loaded and ready to run.
#[derive(Debug, Clone)]
pub struct Exploration {
    /// The spec.
    pub spec: SpecFile,
    /// The spec file's path.
    pub spec_path: PathBuf,
    /// The base design.
    pub base: DesignFile,
    /// The candidate space.
    pub grid: Grid,
    /// How candidates are scored.
    pub model: Model,
    /// The cutting sets a written design resolves to (for the wall rule).
    pub sets: ProcessSets,
    /// Every file the exploration read: the spec, its base design, its tube catalogue, and the
    /// process sets found beside a written design. No output may replace one
    /// (`docs/outputs.md`).
    pub inputs: Vec<PathBuf>,
    /// What predicting the front's accuracy cost, once [`Exploration::predict_front`] ran:
    /// candidates simulated and wall-clock seconds.
    pub prediction_cost: Option<(usize, f64)>,
}

impl Exploration {
    /// Reads the spec, its base design and catalogue. `written_design` is a path where a
    /// written design will live: its process sets are resolved from there, as `dlw build` will.
    ///
    /// # Errors
    /// [`ExploreError`] naming the file, key or value.
    pub fn load(spec_path: &Path, written_design: &Path) -> Result<Self, ExploreError> {
        let spec = SpecFile::read(spec_path)?;
        let dir = spec_path.parent().unwrap_or(Path::new("."));
        let base_path = dir.join(&spec.base);
        let base = DesignFile::read(&base_path)?;
        // The base must pass the rules itself; its checked form is not needed.
        rules::check_file(base.clone())?;
        let library = ProcessLibrary::beside(written_design);
        let sets = library.resolve(&base.process)?;
        let grid = Self::grid(&spec, dir, &base)?;
        let mut inputs = vec![spec_path.to_path_buf(), base_path];
        if spec.vary.tube.is_some() {
            inputs.push(Self::catalogue_path(&spec, dir));
        }
        inputs.extend(library.files(&base.process));
        let count = grid.len().unwrap_or(u64::MAX);
        if count > MAX_CANDIDATES {
            return Err(ExploreError::TooMany {
                count,
                max: MAX_CANDIDATES,
            });
        }
        let mat = &base.materials;
        let model = Model {
            gauge_factor: spec.gauge_factor,
            r0_ohm: spec.r0_ohm,
            saturation_strain: mat.sensor_saturation_strain,
            material_strain_limit: mat.backbone_strain_limit,
            youngs_modulus_pa: mat.youngs_modulus_pa(),
            tendon_offset_mm: base.tendon_offset_mm,
            min_range_deg: 0.0,
            material_within_limit: true,
            no_saturation: true,
            max_stroke_per_deg_mm: f64::INFINITY,
            max_tendon_force_per_deg_n: f64::INFINITY,
            min_sensitivity_ohm_per_deg: 0.0,
        }
        .with_constraints(&spec.constraints);
        Ok(Self {
            spec,
            spec_path: spec_path.to_path_buf(),
            base,
            grid,
            model,
            sets,
            inputs,
            prediction_cost: None,
        })
    }

    /// The tube catalogue a spec names (default `tubes.toml` beside it).
    fn catalogue_path(spec: &SpecFile, dir: &Path) -> PathBuf {
        dir.join(spec.tubes.as_deref().unwrap_or(Path::new("tubes.toml")))
    }

    /// The grid: each varied axis, or the base design's value.
    fn grid(spec: &SpecFile, dir: &Path, base: &DesignFile) -> Result<Grid, ExploreError> {
        let v = &spec.vary;
        let tubes = match &v.tube {
            Some(ids) => {
                let path = Self::catalogue_path(spec, dir);
                Catalogue::read(&path)?.pick(ids, &path)?
            }
            None => vec![Tube {
                id: "base".into(),
                outer_radius_mm: base.outer_radius_mm,
                inner_radius_mm: base.inner_radius_mm,
                source: "the base design".into(),
            }],
        };
        for (name, empty) in [
            ("vary.tube", v.tube.as_ref().is_some_and(Vec::is_empty)),
            ("vary.style", v.style.as_ref().is_some_and(Vec::is_empty)),
        ] {
            if empty {
                return Err(SpecError::Value {
                    name: name.into(),
                    value: "[]".into(),
                    limit: "must hold at least one value".into(),
                }
                .into());
            }
        }
        let axis = |a: &Option<Axis>, name: &str, base: f64| match a {
            Some(a) => a.values(&format!("vary.{name}")),
            None => Ok(vec![base]),
        };
        Ok(Grid {
            tubes,
            styles: v.style.clone().unwrap_or_else(|| vec![base.style]),
            notch_arcs_mm: axis(&v.notch_arc_mm, "notch_arc_mm", base.notch_arc_mm)?,
            sensor_arcs_mm: axis(&v.sensor_arc_mm, "sensor_arc_mm", base.sensor_arc_mm)?,
            notch_counts: match &v.notch_count {
                Some(a) => a.counts("vary.notch_count")?,
                None => vec![base.notch_count],
            },
            notch_widths_mm: axis(&v.notch_width_mm, "notch_width_mm", base.notch_width_mm)?,
            notch_spacings_mm: axis(
                &v.notch_spacing_mm,
                "notch_spacing_mm",
                base.notch_spacing_mm,
            )?,
        })
    }

    /// Candidates in the grid.
    pub fn candidate_count(&self) -> u64 {
        self.grid.len().unwrap_or(u64::MAX)
    }

    /// Scores every candidate in parallel; `progress` is called with the number just scored.
    pub fn screen(&self, progress: &(dyn Fn(u64) + Sync)) -> Screen {
        let n = self.candidate_count();
        let chunks = n.div_ceil(CHUNK);
        let mut screen = (0..chunks)
            .into_par_iter()
            .fold(Screen::default, |mut s, chunk| {
                let (from, to) = (chunk * CHUNK, ((chunk + 1) * CHUNK).min(n));
                for index in from..to {
                    let params = self.grid.params(index);
                    s.add(index, params, evaluate(&params, &self.model));
                }
                progress(to - from);
                s
            })
            .reduce(Screen::default, Screen::merge);
        screen.survivors.sort_unstable_by_key(|c| c.index);
        screen
    }

    /// The design rules `dlw build` runs, on one candidate.
    ///
    /// # Errors
    /// Every rule it breaks.
    pub fn rule_check(&self, params: &Params) -> Result<(), Vec<Violation>> {
        let file = params.apply(&self.base, self.base.name.clone());
        rules::check_file(file.clone()).map_err(|e| e.violations)?;
        let wall = rules::check_wall(&file, &self.sets);
        if wall.is_empty() {
            Ok(())
        } else {
            Err(wall)
        }
    }

    /// Runs the design rules on the screen's survivors (in parallel) and keeps those that pass.
    ///
    /// # Errors
    /// [`ExploreError::Infeasible`] naming the binding constraint (or the design rule most
    /// survivors break) when nothing is left.
    pub fn check_rules(
        &self,
        screen: &Screen,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Vec<Candidate>, ExploreError> {
        if screen.survivors.is_empty() {
            return Err(ExploreError::Infeasible(self.binding(screen)));
        }
        if screen.survivors_total > MAX_SURVIVORS {
            return Err(ExploreError::TooManySurvivors {
                count: screen.survivors_total,
                max: MAX_SURVIVORS,
            });
        }
        let checked: Vec<(Candidate, Option<Violation>)> = screen
            .survivors
            .par_iter()
            .map(|c| {
                let r = self.rule_check(&c.params);
                progress(1);
                (*c, r.err().and_then(|v| v.into_iter().next()))
            })
            .collect();
        let feasible: Vec<Candidate> = checked
            .iter()
            .filter(|(_, v)| v.is_none())
            .map(|(c, _)| *c)
            .collect();
        if feasible.is_empty() {
            return Err(ExploreError::Infeasible(rules_binding(&checked)));
        }
        Ok(feasible)
    }

    /// The sentence naming the constraint that binds when no candidate survives the screen.
    pub fn binding(&self, screen: &Screen) -> String {
        let valid = screen.evaluated - screen.geometry_refused;
        if valid == 0 {
            let example = self.geometry_example();
            return format!(
                "the geometry refuses all {} candidates (for example {example}); widen the tube or narrow the notch and sensor arcs",
                screen.evaluated
            );
        }
        let k = self.binding_index(screen);
        let c = Constraint::ALL[k];
        let mut msg = format!(
            "the binding constraint is {}: {} of {} candidates with a valid geometry fail it",
            c.describe(&self.model),
            screen.failing[k],
            valid
        );
        if let Some(best) = screen.best_any[k] {
            msg.push_str(&format!(
                "; the best of all candidates reaches {} (needs {})",
                fmt_sig(best),
                fmt_sig(c.limit(&self.model))
            ));
        }
        if screen.failing_only[k] > 0 {
            msg.push_str(&format!(
                "; {} candidates fail only it",
                screen.failing_only[k]
            ));
        }
        let others: Vec<String> = Constraint::ALL
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != k && screen.failing[j] > 0)
            .map(|(j, c)| format!("{} {}", c.key(), screen.failing[j]))
            .collect();
        if !others.is_empty() {
            msg.push_str(&format!("; other constraints fail: {}", others.join(", ")));
        }
        msg
    }

    /// Which constraint binds: the one whose best value over all candidates falls furthest
    /// short of its limit (no candidate meets it); when each is met by some candidate but never
    /// all together, the one that alone stops the most candidates.
    fn binding_index(&self, screen: &Screen) -> usize {
        // A constraint no candidate fails (or one the spec turned off) cannot bind.
        let shortfall = |k: usize| match screen.best_any[k] {
            Some(b) if screen.failing[k] > 0 => Constraint::ALL[k].shortfall(b, &self.model),
            _ => 0.0,
        };
        let worst = (0..6).max_by(|&a, &b| shortfall(a).total_cmp(&shortfall(b)));
        match worst {
            Some(k) if shortfall(k) > 0.0 => k,
            _ => (0..6)
                .max_by_key(|&k| (screen.failing_only[k], screen.failing[k]))
                .unwrap_or(0),
        }
    }

    /// The geometry's refusal of the first candidate, for the message when it refuses all.
    fn geometry_example(&self) -> String {
        let p = self.grid.params(0);
        let file = p.apply(&self.base, self.base.name.clone());
        match crate::design::Design::from_file(file) {
            Err(e) => e.to_string(),
            Ok(_) => "a tendon outside the lumen".into(),
        }
    }

    /// Indices into `feasible` of the Pareto front of the spec's objectives that the grid's
    /// screen scores (the predicted ones come after, [`Exploration::predict_front`]).
    pub fn front(&self, feasible: &[Candidate]) -> Vec<usize> {
        let signed: Vec<(Metric, f64)> = self
            .spec
            .objectives
            .signed()
            .into_iter()
            .filter(|(m, _)| !m.is_predicted())
            .collect();
        if signed.is_empty() {
            // The spec refuses predicted objectives alone; without objectives nothing is on the
            // front.
            return Vec::new();
        }
        let points: Vec<Vec<f64>> = feasible
            .iter()
            .map(|c| signed.iter().map(|&(m, s)| s * c.metrics.get(m)).collect())
            .collect();
        front_with_ties(&points, TIE_RELATIVE)
    }

    /// Whether the spec asks for a predicted accuracy.
    pub fn predicts(&self) -> bool {
        self.spec
            .objectives
            .signed()
            .iter()
            .any(|(m, _)| m.is_predicted())
    }

    /// Predicts the accuracy of every candidate of `front` with the shipped twin (a short
    /// simulation each, in parallel) and returns the Pareto front of those candidates on
    /// every objective, the predicted ones included. Candidates off `front` are not simulated.
    ///
    /// # Errors
    /// [`ExploreError::Twin`] if the shipped twin does not read.
    pub fn predict_front(
        &mut self,
        feasible: &mut [Candidate],
        front: &[usize],
    ) -> Result<Vec<usize>, ExploreError> {
        let clock = std::time::Instant::now();
        let predictor = Predictor::paper(self.model.gauge_factor)?;
        let files: Vec<DesignFile> = front
            .iter()
            .map(|&i| feasible[i].params.apply(&self.base, self.base.name.clone()))
            .collect();
        for (&i, p) in front.iter().zip(predictor.predict_all(&files)) {
            feasible[i].metrics.predicted = p;
        }
        self.prediction_cost = Some((front.len(), clock.elapsed().as_secs_f64()));
        let signed = self.spec.objectives.signed();
        let points: Vec<Vec<f64>> = front
            .iter()
            .map(|&i| {
                signed
                    .iter()
                    .map(|&(m, s)| s * feasible[i].metrics.get(m))
                    .collect()
            })
            .collect();
        Ok(pareto::front(&points)
            .into_iter()
            .map(|k| front[k])
            .collect())
    }

    /// The best `k` of the front: ordered by the first objective (best first), then the next.
    pub fn best(&self, feasible: &[Candidate], front: &[usize], k: usize) -> Vec<usize> {
        let signed = self.spec.objectives.signed();
        // Ordered by the tied objectives, so that designs equal in one are ordered by the next.
        let points: Vec<Vec<f64>> = front
            .iter()
            .map(|&i| {
                signed
                    .iter()
                    .map(|&(m, s)| s * feasible[i].metrics.get(m))
                    .collect()
            })
            .collect();
        let points = tied(&points, TIE_RELATIVE);
        let mut order: Vec<usize> = (0..front.len()).collect();
        order.sort_by(|&a, &b| {
            for (x, y) in points[a].iter().zip(&points[b]) {
                match y.total_cmp(x) {
                    std::cmp::Ordering::Equal => continue,
                    o => return o,
                }
            }
            feasible[front[a]].index.cmp(&feasible[front[b]].index)
        });
        order.truncate(k);
        order.into_iter().map(|p| front[p]).collect()
    }
}

/// The sentence naming the design rule most survivors break.
fn rules_binding(checked: &[(Candidate, Option<Violation>)]) -> String {
    let mut counts: Vec<(String, usize, String)> = Vec::new();
    for v in checked.iter().filter_map(|(_, v)| v.as_ref()) {
        let debug = format!("{v:?}");
        let kind = debug
            .split([' ', '{', '('])
            .next()
            .unwrap_or_default()
            .to_string();
        match counts.iter_mut().find(|(k, _, _)| *k == kind) {
            Some(entry) => entry.1 += 1,
            None => counts.push((kind, 1, v.to_string())),
        }
    }
    counts.sort_by_key(|c| std::cmp::Reverse(c.1));
    let (_, n, example) = counts.first().cloned().unwrap_or_default();
    format!(
        "all {} candidates that meet the constraints break a design rule; the binding one is the rule {n} of them break, for example: {example}",
        checked.len()
    )
}

/// A number with four significant figures, for messages.
fn fmt_sig(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e4 || x.abs() < 1e-3) {
        format!("{x:.3e}")
    } else {
        format!("{x:.4}")
    }
}

#[cfg(test)]
mod tests;
