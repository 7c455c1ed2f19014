//! Runtime estimator: turns a sensing joint's divider voltage into its bending angle.
//!
//! Placeholder crate root; the models arrive with the estimator issue.
#![cfg_attr(not(feature = "std"), no_std)]
