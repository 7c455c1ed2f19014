//! `dlw characterize` as a library call: a [`CharacterizeRequest`] (recording, joint, kind,
//! configs, options) in, a [`Characterization`] (the kind's result, its report page, its JSON)
//! out.

use std::path::PathBuf;

use dlw_geometry::Joint;
use serde::Serialize;

use super::{
    estimate, loops, planes, rate, relaxation, AnalysisKind, CharacterizeError, EstimationResult,
    LoopsResult, NamedConfig, Options, RateResult, RelaxationResult,
};
use crate::analysis::{Analysis, Placement};
use crate::recording::Recording;
use crate::replay::load_config;
use crate::report::Page;

/// What to characterize: everything `dlw characterize` takes besides its output folder.
#[derive(Debug, Clone)]
pub struct CharacterizeRequest<'a> {
    /// The recording analysed.
    pub recording: &'a Recording,
    /// Its name, for the report and the JSON's `recording` (the command gives its path).
    pub recording_name: String,
    /// The recorded joint (the design's joint).
    pub joint: &'a Joint,
    /// The design's name, for the report's title and messages.
    pub design_name: String,
    /// Where the design came from, for the report's text (the command gives its path).
    pub design_source: String,
    /// The analysis; `None`: the one for the protocol `rig.toml` states ([`AnalysisKind::of_recording`]).
    pub kind: Option<AnalysisKind>,
    /// The estimator config files of the `estimation` analysis (none for the others), each
    /// named in the results by its file stem.
    pub configs: Vec<PathBuf>,
    /// Settings shared by the kinds.
    pub options: Options,
}

/// One kind's result.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum KindResult {
    /// Resistance-strain loops and fits.
    Loops(LoopsResult),
    /// Rate dependence.
    Rate(RateResult),
    /// Relaxation during holds.
    Relaxation(RelaxationResult),
    /// Angle estimation with each config.
    Estimation(EstimationResult),
}

impl KindResult {
    /// The result as the one analysis interface.
    fn analysis(&self) -> &dyn AnalysisSection {
        match self {
            Self::Loops(r) => r,
            Self::Rate(r) => r,
            Self::Relaxation(r) => r,
            Self::Estimation(r) => r,
        }
    }
}

/// [`Analysis`] without its `Serialize` bound, so that the kinds' results can be held as one.
trait AnalysisSection {
    fn summary(&self) -> String;
    fn add_to_page(&self, page: &mut Page, at: Placement<'_>);
}

impl<T: Analysis> AnalysisSection for T {
    fn summary(&self) -> String {
        Analysis::summary(self)
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        Analysis::add_to_page(self, page, at);
    }
}

/// A characterization: the kind run and its result. Serializes to what `dlw characterize
/// --json` prints (`kind`, `recording`, `report`, then the kind's own keys).
#[derive(Debug, Clone, Serialize)]
pub struct Characterization {
    /// The analysis run.
    pub kind: AnalysisKind,
    /// The recording's name, as the request gave it.
    pub recording: String,
    /// The report page's path, once the caller has written it.
    pub report: Option<PathBuf>,
    /// The kind's result.
    #[serde(flatten)]
    pub result: KindResult,
    /// What the report's opening paragraph says of the inputs.
    #[serde(skip)]
    inputs: Inputs,
}

/// The inputs as the report's title and opening paragraph name them.
#[derive(Debug, Clone)]
struct Inputs {
    design_name: String,
    design_source: String,
    samples: usize,
    sample_hz: f64,
    prefilter: String,
}

/// Runs the analysis `request` asks for, or the one its recording's protocol names.
///
/// # Errors
/// [`CharacterizeError`]: no kind asked for and none stated by the recording; configs given
/// to a kind other than `estimation`; a sensor column the design does not carry; what the
/// kind's own analysis refuses.
pub fn characterize(
    request: &CharacterizeRequest<'_>,
) -> Result<Characterization, CharacterizeError> {
    let min_hold_s = request.options.min_hold_s;
    if !(min_hold_s.is_finite() && min_hold_s > 0.0) {
        return Err(CharacterizeError::MinHold { min_hold_s });
    }
    let name = &request.recording_name;
    let kind = match request.kind {
        Some(k) => k,
        None => AnalysisKind::of_recording(request.recording).map_err(|e| {
            CharacterizeError::Choose {
                recording: name.clone(),
                source: Box::new(e),
            }
        })?,
    };
    if kind != AnalysisKind::Estimation && !request.configs.is_empty() {
        return Err(CharacterizeError::ConfigsForOtherKind { kind: kind.name() });
    }
    let configs = request
        .configs
        .iter()
        .map(|p| {
            Ok(NamedConfig {
                name: p
                    .file_stem()
                    .map_or_else(|| p.display().to_string(), |s| s.to_string_lossy().into()),
                config: load_config(p)?,
            })
        })
        .collect::<Result<Vec<_>, CharacterizeError>>()?;
    let (recording, joint, options) = (request.recording, request.joint, &request.options);
    let planes = planes(recording, joint, &request.design_name)?;
    let result = match kind {
        AnalysisKind::Loops => loops(recording, joint, &planes, options).map(KindResult::Loops),
        AnalysisKind::Rate => rate(recording, joint, &planes, options).map(KindResult::Rate),
        AnalysisKind::Relaxation => {
            relaxation(recording, joint, &planes, options).map(KindResult::Relaxation)
        }
        AnalysisKind::Estimation => {
            estimate(recording, &configs, options).map(KindResult::Estimation)
        }
    }
    .map_err(|e| CharacterizeError::Analysis {
        kind: kind.name(),
        recording: name.clone(),
        source: Box::new(e),
    })?;
    Ok(Characterization {
        kind,
        recording: request.recording_name.clone(),
        report: None,
        result,
        inputs: Inputs {
            design_name: request.design_name.clone(),
            design_source: request.design_source.clone(),
            samples: recording.samples.len(),
            sample_hz: recording.rig.sample_hz,
            prefilter: options.prefilter.to_string(),
        },
    })
}

impl Characterization {
    /// The report's page: a title, what was analysed, and the kind's section.
    pub fn report_page(&self) -> Page {
        let i = &self.inputs;
        let mut page = Page::new(format!(
            "Characterization ({}): {}",
            self.kind.name(),
            i.design_name
        ));
        page.text(format!(
            "Recording {}, {} samples at {} Hz; design {}. Strain from the tracker angle \
             (Eq. 3), resistance from the divider voltage (Eq. 4), both through the prefilter {}.",
            self.recording, i.samples, i.sample_hz, i.design_source, i.prefilter
        ));
        Analysis::add_to_page(self, &mut page, Placement::ALONE);
        page
    }
}

impl AnalysisKind {
    /// The heading of the kind's section, with the paper's place for it.
    pub fn heading(self) -> &'static str {
        match self {
            AnalysisKind::Loops => "Resistance-strain loops (Section IV-A1, Fig. 4, Table III)",
            AnalysisKind::Rate => "Rate dependence (Section IV-A2, Fig. 5)",
            AnalysisKind::Relaxation => "Relaxation (Section IV-A3, Fig. 6)",
            AnalysisKind::Estimation => "Angle estimation (Section IV-B, Tables IV-V, Figs. 7-8)",
        }
    }
}

impl Analysis for Characterization {
    /// The kind's summary, and the report's path once written.
    fn summary(&self) -> String {
        let mut out = self.result.analysis().summary();
        if let Some(report) = &self.report {
            out.push_str(&format!("report {}\n", report.display()));
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        page.heading(at.titled(self.kind.heading()));
        self.result.analysis().add_to_page(page, at);
    }
}
