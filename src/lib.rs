//! `dlw`: from a sensing continuum-robot joint's design parameters to a finished part and a
//! working sensor.
//!
//! The crate is the library half of the `dlw` command. Its modules stand on three floors, and
//! each uses only modules on its own floor or below (`docs/architecture.md` draws the graph;
//! `scripts/deps.py` lists it from the code, and `tests/architecture.rs` holds it free of
//! cycles).
//!
//! # Shared floor (used by both sides, using nothing of `dlw` above it)
//! - [`stats`]: the shared statistics (`min_max`, `moments`, `slope`, `rmse`, medians, linear
//!   interpolation) and their one NaN policy;
//! - [`fixed`]: the one number formatter (programs, drawings, templates, CSV);
//! - [`finite`]: JSON that never carries NaN or infinity;
//! - [`limits`]: the plausible ranges every input is checked against;
//! - [`output`]: the output policy (never replace without `--force`, never an input), atomic
//!   writes, so a failed command leaves no partial file, and the one bounded reader;
//! - [`report`]: HTML report pages and their SVG charts;
//! - [`sensor`]: which sensor (`Sensor`, `Sensors`): the one typed sensor identity.
//!
//! # Fabrication: design → layout → toolpath → post
//! - [`design`]: design files (the paper's Table I plus fabrication tables), read and validated;
//! - [`layout`]: the unrolled joint (notches, sensor traces, leads, pads, parting line) in the
//!   drawing frame;
//! - [`process`], [`machine`]: laser parameter sets (Table II) and machine profiles;
//! - [`drawing`]: DXF for designers (written and read back) and SVG for people;
//! - [`rules`]: the design rules every command runs (errors block output, warnings are
//!   printed);
//! - [`toolpath`]: the dialect-free laser plan (sensor → notches → parting);
//! - [`post`]: post-processors that write the plan in a controller's dialect;
//! - [`sheet`]: the operator's setup sheet, an emitter like the posts;
//! - [`robot`]: several joints on one tube, described: the robot file, its leads routed past
//!   each other's notches to one pad section, the crosstalk, one layout for the whole robot
//!   (`docs/robots.md`). It reuses the joint's layout, and bends it not; the sensing side
//!   reads it too;
//! - [`job`]: a design made into a program and a setup sheet for one machine;
//! - [`build`]: what `dlw build`, `program`, `draw` and `import-dxf` make of a joint or a robot:
//!   the part with its process sets and machine profile, a drawing read back and checked, the
//!   drawings, the job (a robot's through the joint's planner) and the build folder.
//!
//! # Sensing: recording → fit → config → estimator; recording → discover → scenario
//! - [`recording`]: recording folders (`rig.toml`, `data.csv`), read, checked and written, with
//!   their provenance, protocol and ground-truth angles; the floor of the sensing side;
//! - [`import`]: recordings from a bench's own files (TDMS, LVM, CSV and a tracker log),
//!   aligned and checked;
//! - [`sim`]: the bench simulator (stroke → angle → strain → resistance → voltage → ADC),
//!   writing the same recordings;
//! - [`signal`]: observations of a sensor in a recording, prefilters, cycles and phases, the
//!   line fit: what every analysis reads a recording through;
//! - [`analysis`]: the one interface every analysis's result implements (JSON, summary, report
//!   section);
//! - [`fit`]: linear and Prandtl-Ishlinskii models fitted to a recording, and the estimator
//!   config they make;
//! - [`replay`]: the runtime estimator (`dlw-estimator`) over a recording (`dlw estimate`), and
//!   its config files;
//! - [`fluoro`]: the joint angle from fluoroscopy frames (the phantom's ground truth), and
//!   synthetic frames to try it on;
//! - [`characterize`]: the paper's characterization analyses over a recording (Section IV-A,
//!   IV-B);
//! - [`discover`]: where the simulator and a recording disagree, which effect is missing, and
//!   the gap once it is added;
//! - [`control`]: open- and closed-loop control of a joint on the simulated bench (Section
//!   IV-C);
//! - [`reproduce`]: the paper's Section IV on the simulator (the ideal bench or a calibrated
//!   twin), Tables III-VI side by side;
//! - [`calibrate`]: the simulator's bench parameters fitted to the paper's measured tables (a
//!   twin of the bench).
//!
//! # Above both sides
//! - [`explore`]: from requirements to joints: candidates scored with the mechanics and the
//!   sensing model, the design rules, the Pareto front, and the twin's predicted accuracy of
//!   the front's designs.
//!
//! The cross-section and strain math lives in the `dlw-geometry` crate, shared with the
//! runtime estimator (`dlw-estimator`).

pub mod analysis;
pub mod build;
pub mod calibrate;
pub mod characterize;
pub mod control;
pub mod design;
pub mod discover;
pub mod drawing;
pub mod explore;
pub mod finite;
pub mod fit;
pub mod fixed;
pub mod fluoro;
pub mod import;
pub mod job;
pub mod layout;
pub mod limits;
pub mod machine;
pub mod output;
pub mod post;
pub mod process;
pub mod recording;
pub mod replay;
pub mod report;
pub mod reproduce;
pub mod robot;
pub mod rules;
pub mod sensor;
pub mod sheet;
pub mod signal;
pub mod sim;
pub mod stats;
pub mod toolpath;
