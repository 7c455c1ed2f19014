//! `dlw`: from a sensing continuum-robot joint's design parameters to a finished part and a
//! working sensor.
//!
//! The crate is the planner, fitting, simulation and the CLI's library half. The pieces, each in
//! its own folder:
//! - [`design`]: design files (the paper's Table I plus fabrication tables), read and validated;
//! - [`layout`]: the unrolled joint (notches, sensor traces, leads, pads, parting line) in the
//!   drawing frame;
//! - [`drawing`]: drawings of the joint: DXF for designers (written and read back), SVG for people;
//! - [`rules`]: the design rules every command runs (errors block output, warnings are printed);
//! - [`output`]: writing files atomically, so a failed command never leaves a partial file.
//!
//! The cross-section and strain math lives in the `dlw-geometry` crate, shared with the
//! runtime estimator.

pub mod design;
pub mod drawing;
pub mod layout;
pub mod output;
pub mod rules;
