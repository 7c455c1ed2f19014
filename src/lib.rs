//! `dlw`: from a sensing continuum-robot joint's design parameters to a finished part and a
//! working sensor.
//!
//! The crate is the planner, fitting, simulation and the CLI's library half. The pieces, each in
//! its own folder:
//! - [`design`]: design files (the paper's Table I plus fabrication tables), read and validated;
//! - [`layout`]: the unrolled joint (notches, sensor traces, leads, pads, parting line) in the
//!   drawing frame;
//! - [`drawing`]: drawings of the joint: DXF for designers (written and read back), SVG for
//!   people;
//! - [`explore`]: from requirements to joints: a grid of candidates scored with the mechanics
//!   and the sensing model, the design rules, the Pareto front (`dlw explore`);
//! - [`rules`]: the design rules every command runs (errors block output, warnings are printed);
//! - [`robot`]: several joints on one tube: the robot file, its leads routed to one pad section,
//!   the crosstalk, one layout and one program for the whole robot (`docs/robots.md`);
//! - [`process`], [`machine`]: laser parameter sets (Table II) and machine profiles;
//! - [`toolpath`]: the dialect-free laser plan (sensor → notches → parting);
//! - [`sheet`]: the operator's setup sheet, an emitter like the posts;
//! - [`post`]: post-processors that write the plan in a controller's dialect;
//! - [`job`]: a design made into a program and a setup sheet for one machine;
//! - [`output`]: writing files atomically, so a failed command never leaves a partial file;
//! - [`analysis`]: the one interface every analysis's result implements (JSON, summary, report
//!   section);
//! - [`sensor`]: which sensor (`Sensor`, `Sensors`): the one typed sensor identity;
//! - [`characterize`]: the paper's characterization analyses over a recording (Section IV-A, IV-B);
//! - [`discover`]: where the simulator and a recording disagree, which effect is missing, and
//!   the gap once it is added;
//! - [`control`]: open- and closed-loop control of a joint on the simulated bench (Section IV-C);
//! - [`reproduce`]: the paper's Section IV on the simulator, Tables III-VI side by side;
//! - [`replay`]: running the runtime estimator (`dlw-estimator`) over a recording, and its
//!   config files;
//! - [`recording`]: recording folders (`rig.toml`, `data.csv`), read, checked and written, with
//!   their provenance (simulated or imported); depends on nothing above it;
//! - [`stats`]: the shared statistics (`min_max`, `moments`, `slope`, `rmse`, medians) and their
//!   one NaN policy;
//! - [`fixed`]: the one number formatter (programs, drawings, templates, CSV);
//! - [`fluoro`]: the joint angle from fluoroscopy frames (the phantom's ground truth), and
//!   synthetic frames to try it on;
//! - [`sim`]: the bench simulator (stroke → angle → strain → resistance → voltage → ADC) and
//!   recording folders.
//!
//! The cross-section and strain math lives in the `dlw-geometry` crate, shared with the
//! runtime estimator.

pub mod analysis;
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
pub mod sim;
pub mod stats;
pub mod toolpath;
