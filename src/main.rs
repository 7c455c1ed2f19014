//! `dlw`: from a sensing joint's design to drawings, laser programs and a working sensor.

fn main() {}
