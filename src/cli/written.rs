//! What every command that writes a result shares: `-o` and `--force` ([`Output`], or
//! [`DefaultedOutput`] where `-o` has a default), with `--json` beside them ([`Written`]),
//! flattened into the command's own arguments (as [`super::scenario_args::ScenarioArgs`] is),
//! and the claim of the output against the command's inputs (docs/outputs.md) that must come
//! before any work. What `-o` holds is each command's own: its `--help` says so.

use std::ops::Deref;
use std::path::{Path, PathBuf};

use dlw::output::{self, OutputError};

/// `-o` and `--force`.
#[derive(Debug, clap::Args)]
pub struct Output {
    /// Output: what it holds is in the command's description (`--help`). An existing one is
    /// replaced only with --force.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    pub force: bool,
}

impl Output {
    /// Claims `-o` as an output **file** of a command reading `inputs`.
    ///
    /// # Errors
    /// [`output::claim`]'s.
    pub fn claim<P: AsRef<Path>>(
        &self,
        inputs: impl IntoIterator<Item = P>,
    ) -> Result<(), OutputError> {
        output::claim(&self.output, inputs, self.force)
    }

    /// Claims `-o` as an output **folder** of a command reading `inputs`.
    ///
    /// # Errors
    /// [`output::claim_folder`]'s.
    pub fn claim_folder<P: AsRef<Path>>(
        &self,
        inputs: impl IntoIterator<Item = P>,
    ) -> Result<(), OutputError> {
        output::claim_folder(&self.output, inputs, self.force)
    }

    /// Claims `-o` and the command's other outputs (`more`, e.g. a report folder) together,
    /// as outputs of a command reading `inputs`; they must differ from each other.
    ///
    /// # Errors
    /// [`output::claim_all`]'s.
    pub fn claim_with<P: AsRef<Path>>(
        &self,
        more: &[&Path],
        inputs: impl IntoIterator<Item = P>,
    ) -> Result<(), OutputError> {
        let outputs: Vec<&Path> = std::iter::once(self.output.as_path())
            .chain(more.iter().copied())
            .collect();
        output::claim_all(&outputs, inputs, self.force)
    }
}

/// `-o`, `--force` and `--json`.
#[derive(Debug, clap::Args)]
pub struct Written {
    /// `-o` and `--force`.
    #[command(flatten)]
    pub to: Output,
    /// Print the result as JSON.
    #[arg(long)]
    pub json: bool,
}

/// A `Written` is claimed and read as its [`Output`].
impl Deref for Written {
    type Target = Output;

    fn deref(&self) -> &Output {
        &self.to
    }
}

/// `-o` with a default the command works out from its inputs, and `--force`.
#[derive(Debug, clap::Args)]
pub struct DefaultedOutput {
    /// Output: what it holds, and its default, are in the command's description (`--help`). An
    /// existing one is replaced only with --force.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    pub force: bool,
}

impl DefaultedOutput {
    /// `-o`, or `default` without it.
    pub fn or(&self, default: impl FnOnce() -> PathBuf) -> Output {
        Output {
            output: self.output.clone().unwrap_or_else(default),
            force: self.force,
        }
    }
}
