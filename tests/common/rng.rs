//! The seeded random numbers and the white + AR(1) noise of the tests' own recording
//! generators (`second_generator`, `other_forms`): xorshift64* with Box-Muller normals, no
//! extra crates, and not the simulator's generator.
#![allow(dead_code)]

/// xorshift64* with Box-Muller normals.
pub struct Rng(u64);

impl Rng {
    /// A generator seeded by `seed`.
    pub fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        ((x >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Standard normal.
    pub fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// White noise of standard deviation `white` plus AR(1) noise of standard deviation `ar` and
/// correlation time `tau_s`, sampled at `sample_hz`.
pub struct Noise {
    white: f64,
    ar: f64,
    phi: f64,
    state: f64,
}

impl Noise {
    /// The noise, its AR state drawn from `rng`.
    pub fn new(white: f64, ar: f64, tau_s: f64, sample_hz: f64, rng: &mut Rng) -> Self {
        Noise {
            white,
            ar,
            phi: (-1.0 / (sample_hz * tau_s)).exp(),
            state: ar * rng.normal(),
        }
    }

    /// The next sample.
    pub fn next(&mut self, rng: &mut Rng) -> f64 {
        self.state =
            self.phi * self.state + (1.0 - self.phi * self.phi).sqrt() * self.ar * rng.normal();
        self.state + self.white * rng.normal()
    }
}
