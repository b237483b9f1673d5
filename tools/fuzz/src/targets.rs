//! The targets: how an input is drawn for (target, seed, iteration), how it is run, and how
//! its outcome is counted.

use std::panic::{self, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rne_codegen_core::{
    generate, ForwardDynamicsMethod, GenerationOptions, Kernel, MimicMode, ParameterMode,
    ScalarType, Scene,
};
use rne_symbolic::model::Base;
use rne_symbolic::spec::{LoadOptions, RobotFormat};
use rne_symbolic::RobotModel;
use rne_symbolic::{read_robot, Description};

use crate::clarity::naming;
use crate::harness::{self, Outcome};
use crate::mutate::{self, pick, Applied, Focus};
use crate::random_robot::random_robot;
use crate::report::{FailureClass, Report};
use crate::seeds::{seeds, Seed};
use crate::{Config, Target};

/// Moving joints a mutated fixture keeps for the generate target: the others are locked, so
/// that every kernel of a seven-joint arm is built in well under the budget.
const GENERATE_JOINTS: usize = 3;

/// Links a loaded robot may have for the generate target: generating every kernel of a
/// thousand-link chain (which the long-chain mutations make) takes minutes, as it should.
const GENERATE_LINKS: usize = 40;

/// One input: the file a reader is given and how.
#[derive(Clone, Debug)]
pub struct Input {
    /// Its target.
    pub target: Target,
    /// The run's seed.
    pub seed: u64,
    /// Its iteration.
    pub iteration: u64,
    /// The fixture it was mutated from (`random` for a random robot).
    pub seed_file: String,
    /// The file name the reader is given (its errors must name it).
    pub file: String,
    /// The format it is read as.
    pub format: RobotFormat,
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// How it is read.
    pub options: LoadOptions,
    /// The mutations applied, in order.
    pub applied: Vec<Applied>,
    /// The scene and generation options generated from it (generate target).
    pub scene: Option<(Scene, GenerationOptions)>,
}

impl Input {
    /// The fixture and the mutations, for a report.
    pub fn describe(&self) -> String {
        let mutations: Vec<&str> = self
            .applied
            .iter()
            .map(|a| a.description.as_str())
            .collect();
        format!("{}: {}", self.seed_file, mutations.join("; "))
    }

    /// The input of a mutation that panicked: its place only (`--replay` shows the panic).
    fn unmade(target: Target, seed: u64, iteration: u64) -> Input {
        Input {
            target,
            seed,
            iteration,
            seed_file: "(the mutation panicked: replay it)".to_owned(),
            file: String::new(),
            format: RobotFormat::Toml,
            bytes: Vec::new(),
            options: LoadOptions::default(),
            applied: Vec::new(),
            scene: None,
        }
    }

    fn focus(&self) -> Vec<Focus> {
        self.applied.iter().map(|a| a.focus.clone()).collect()
    }
}

/// The seed files of both formats.
#[derive(Clone, Debug)]
pub struct Corpus {
    urdf: Vec<Seed>,
    toml: Vec<Seed>,
}

impl Corpus {
    /// The fixture robot files under `root`.
    pub fn load(root: &std::path::Path) -> std::io::Result<Corpus> {
        Ok(Corpus {
            urdf: seeds(root, RobotFormat::Urdf)?,
            toml: seeds(root, RobotFormat::Toml)?,
        })
    }

    fn of(&self, format: RobotFormat) -> &[Seed] {
        match format {
            RobotFormat::Urdf => &self.urdf,
            RobotFormat::Toml => &self.toml,
        }
    }
}

/// The generator of input `iteration` of `target` in the run seeded `seed`.
fn generator(target: Target, seed: u64, iteration: u64) -> ChaCha8Rng {
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    key[8] = target as u8 + 1;
    let mut rng = ChaCha8Rng::from_seed(key);
    rng.set_stream(iteration);
    rng
}

/// Input `iteration` of `target` in the run `config` says (its seed and longest chains), over
/// the fixtures of `corpus`.
pub fn input(target: Target, corpus: &Corpus, config: &Config, iteration: u64) -> Input {
    let seed = config.seed;
    let longest = config.longest_chain;
    let mut rng = generator(target, seed, iteration);
    let options = LoadOptions {
        symbolic_parameters: rng.gen_bool(0.3),
        strict: rng.gen_bool(0.2),
        free_mimic: rng.gen_bool(0.2),
        exact_right_angles: rng.gen_bool(0.8),
    };
    let mut input = match target {
        Target::Urdf => mutant(&mut rng, corpus, RobotFormat::Urdf, true, longest),
        Target::Toml => mutant(&mut rng, corpus, RobotFormat::Toml, true, longest),
        Target::Generate => generate_input(&mut rng, corpus, longest),
    };
    input.target = target;
    input.seed = seed;
    input.iteration = iteration;
    input.options = options;
    input.file = format!("fuzz-{iteration}/{}", input.file);
    input
}

/// A fixture of `format` with one to four mutations: structure-aware ones, then (when
/// `bytes`) sometimes byte-level ones.
fn mutant(
    rng: &mut ChaCha8Rng,
    corpus: &Corpus,
    format: RobotFormat,
    bytes: bool,
    longest: usize,
) -> Input {
    let seed = pick(rng, corpus.of(format));
    let mut text = seed.text.clone();
    let mut applied = Vec::new();
    let structural = rng.gen_range(usize::from(!bytes)..=3);
    for _ in 0..structural {
        applied.push(match format {
            RobotFormat::Urdf => mutate::urdf::mutate(rng, &mut text, longest),
            RobotFormat::Toml => mutate::toml::mutate(rng, &mut text, longest),
        });
    }
    let mut raw = text.into_bytes();
    let byte_level = if structural == 0 {
        rng.gen_range(1..=2)
    } else {
        usize::from(bytes && rng.gen_bool(0.2))
    };
    for _ in 0..byte_level {
        applied.push(mutate::bytes::mutate(rng, &mut raw));
    }
    Input {
        target: Target::Urdf,
        seed: 0,
        iteration: 0,
        seed_file: seed.path.clone(),
        file: seed
            .path
            .rsplit('/')
            .next()
            .unwrap_or(&seed.path)
            .to_owned(),
        format,
        bytes: raw,
        options: LoadOptions::default(),
        applied,
        scene: None,
    }
}

/// A random robot (three inputs in five) or a mutated fixture, and a random scene.
fn generate_input(rng: &mut ChaCha8Rng, corpus: &Corpus, longest: usize) -> Input {
    let format = if rng.gen_bool(0.5) {
        RobotFormat::Toml
    } else {
        RobotFormat::Urdf
    };
    let mut input = if rng.gen_bool(0.6) {
        let text = random_robot(rng, format);
        let extension = match format {
            RobotFormat::Toml => "toml",
            RobotFormat::Urdf => "urdf",
        };
        Input {
            seed_file: "random".to_owned(),
            file: format!("random.{extension}"),
            bytes: text.into_bytes(),
            ..mutant(rng, corpus, format, false, longest)
        }
    } else {
        mutant(rng, corpus, format, false, longest)
    };
    input.scene = Some(scene(rng));
    input
}

/// Every kernel, with random scene settings and generation options (drawn in a fixed order:
/// the same seed gives the same settings).
fn scene(rng: &mut ChaCha8Rng) -> (Scene, GenerationOptions) {
    let gravity = rng.gen_bool(0.1).then_some([0.0, 0.0, 0.0]);
    let at_rest = rng.gen_bool(0.1);
    let mut options = GenerationOptions {
        outputs: Kernel::ALL.to_vec(),
        parameters: *pick(
            rng,
            &[
                ParameterMode::Constant,
                ParameterMode::Constant,
                ParameterMode::Base,
            ],
        ),
        scalar: *pick(
            rng,
            &[ScalarType::F64, ScalarType::F32, ScalarType::Generic],
        ),
        ..GenerationOptions::default()
    };
    let scene = Scene {
        gravity,
        at_rest,
        mimic: *pick(rng, &[MimicMode::Constrained, MimicMode::Free]),
        friction: rng.gen_bool(0.3),
        ..Scene::default()
    };
    options.forward_dynamics = *pick(
        rng,
        &[
            ForwardDynamicsMethod::Auto,
            ForwardDynamicsMethod::Aba,
            ForwardDynamicsMethod::Ldlt,
        ],
    );
    options.fma = rng.gen_bool(0.2);
    options.derivative_lanes = rng.gen_bool(0.2);
    (scene, options)
}

/// How reading an input ended.
#[derive(Debug)]
struct Read {
    /// The file name the reader was given.
    origin: String,
    /// The model, or the error's message.
    result: Result<RobotModel, String>,
}

/// Reads `input` as a user's file: from memory when it is UTF-8, else from a file on disk (the
/// reader's only way to meet bytes that are not).
fn read(input: &Input) -> Read {
    match std::str::from_utf8(&input.bytes) {
        Ok(text) => Read {
            origin: input.file.clone(),
            result: read_robot(
                Description::text(text, input.format, &input.file),
                &input.options,
            )
            .map_err(|e| e.to_string()),
        },
        Err(_) => read_from_disk(input),
    }
}

fn read_from_disk(input: &Input) -> Read {
    let dir = std::env::temp_dir().join(format!(
        "rne-fuzz-{}-{}",
        std::process::id(),
        input.iteration
    ));
    let path: PathBuf = dir.join(input.file.rsplit('/').next().unwrap_or("robot"));
    let origin = path.display().to_string();
    let written = std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&path, &input.bytes));
    let result = match written {
        Ok(()) => read_robot(Description::file(&path), &input.options).map_err(|e| e.to_string()),
        Err(e) => Err(format!(
            "{origin}: the harness could not write the input: {e}"
        )),
    };
    let _ = std::fs::remove_dir_all(&dir);
    Read { origin, result }
}

/// What is wrong with a model a reader returned, if anything: a parent after its child, a
/// non-finite number, a negative mass.
fn model_fault(model: &RobotModel) -> Option<String> {
    for (i, link) in model.links.iter().enumerate() {
        if link.parent.is_some_and(|p| p >= i) {
            return Some(format!("link {i} comes before its parent"));
        }
    }
    let numeric = model.to_numeric();
    if !numeric.gravity.iter().all(|g| g.is_finite()) {
        return Some(format!("gravity {:?} is not finite", numeric.gravity));
    }
    for link in &numeric.links {
        let values = link.rotation.concat().into_iter().chain(link.translation);
        let values = values
            .chain(link.axis)
            .chain(link.com)
            .chain(link.inertia.concat());
        if !values.into_iter().all(f64::is_finite) || !link.mass.is_finite() || link.mass < 0.0 {
            return Some(format!(
                "link '{}' has non-finite or negative numbers",
                link.name
            ));
        }
    }
    None
}

/// The generator's outcome for one base: a module that lexes, one that does not (the lexer's
/// message), or the generator's error.
type Generated = Result<Result<(), String>, String>;

/// Reads `input` and, when it loads, generates every kernel of its scene on a fixed and on a
/// floating base.
fn read_and_generate(input: &Input) -> (Read, Vec<Generated>) {
    let read = read(input);
    let (Ok(model), Some((scene, options))) = (&read.result, &input.scene) else {
        return (read, Vec::new());
    };
    if model.links.len() > GENERATE_LINKS {
        return (read, Vec::new());
    }
    let mut scene = scene.clone();
    scene.lock = joints_after_mimic(model, scene.mimic)
        .into_iter()
        .skip(GENERATE_JOINTS)
        .map(|joint| (joint, 0.3))
        .collect();
    let generated = [Base::Fixed, Base::Floating]
        .into_iter()
        .map(|base| {
            let mut model = model.clone();
            model.set_base(base);
            generate(&model, &scene, options, &read.origin)
                .map(|module| module.items().map(drop).map_err(|e| e.to_string()))
                .map_err(|e| e.to_string())
        })
        .collect();
    (read, generated)
}

/// The joint variables of `model` once `mimic` has constrained its followers (as many as it
/// has when they cannot be constrained: the generator reports why).
fn joints_after_mimic(model: &RobotModel, mimic: MimicMode) -> Vec<String> {
    let mut constrained = model.clone();
    if mimic == MimicMode::Constrained && constrained.constrain_mimic_joints().is_err() {
        return model.joint_names();
    }
    constrained.joint_names()
}

/// Counts a read: loaded (a fault of the model is a failure) or rejected (an error that does
/// not name the file is a failure).
fn count_read(report: &mut Report, input: &Input, read: &Read) {
    match &read.result {
        Ok(model) => {
            report.loaded += 1;
            if let Some(fault) = model_fault(model) {
                report.fail(FailureClass::BadModel, fault, input);
            }
        }
        Err(message) => {
            report.rejected += 1;
            let named = naming(message, &read.origin, &input.focus());
            if !named.file {
                report.fail(FailureClass::UnclearError, message.clone(), input);
            }
            let tally = |count: &mut (u64, u64), named: Option<bool>| {
                if let Some(named) = named {
                    count.0 += 1;
                    count.1 += u64::from(named);
                }
            };
            if named.element == Some(false) && named.field == Some(false) {
                report.sample(
                    "reader error naming neither aimed element nor field: ",
                    message,
                );
            }
            tally(&mut report.element, named.element);
            tally(&mut report.field, named.field);
        }
    }
}

fn count_generated(report: &mut Report, input: &Input, generated: &[Generated]) {
    for outcome in generated {
        match outcome {
            Ok(Ok(())) => report.generated += 1,
            Ok(Err(lex)) => report.fail(FailureClass::BadModule, lex.clone(), input),
            Err(e) => {
                report.generate_errors += 1;
                report.sample("generator error: ", e);
            }
        }
    }
}

/// Runs `target` as `config` says, calling `progress` after every input.
pub fn run(
    target: Target,
    config: &Config,
    progress: &mut dyn FnMut(&Report),
) -> std::io::Result<Report> {
    let corpus = Arc::new(Corpus::load(&config.root)?);
    let _quiet = harness::silence_panics();
    let mut report = Report::new(target, config.seed);
    let start = Instant::now();
    let mut iteration = config.first;
    loop {
        let out_of_time = config
            .seconds
            .is_some_and(|s| start.elapsed().as_secs_f64() >= s);
        let out_of_inputs = config.iterations.is_some_and(|n| report.inputs >= n);
        if out_of_time || out_of_inputs {
            break;
        }
        // A mutation that panics is the harness's bug, reported as such (on this thread, the
        // panic hook records it instead of printing it).
        match panic::catch_unwind(AssertUnwindSafe(|| {
            input(target, &corpus, config, iteration)
        })) {
            Ok(input) => run_one(&mut report, input, config),
            Err(_) => {
                let unmade = Input::unmade(target, config.seed, iteration);
                report.inputs += 1;
                report.fail(
                    FailureClass::Mutator,
                    "the mutation panicked".to_owned(),
                    &unmade,
                );
            }
        }
        report.elapsed = start.elapsed();
        progress(&report);
        iteration += 1;
    }
    Ok(report)
}

fn run_one(report: &mut Report, input: Input, config: &Config) {
    report.inputs += 1;
    let shared = Arc::new(input);
    let work = Arc::clone(&shared);
    let outcome = harness::run(config.budget, move || read_and_generate(&work));
    let input = &*shared;
    match outcome {
        Outcome::Done((read, generated), elapsed) => {
            if elapsed > report.slowest.0 {
                report.slowest = (elapsed, input.iteration);
            }
            count_read(report, input, &read);
            count_generated(report, input, &generated);
            if input.scene.is_some() && read.result.is_ok() && generated.is_empty() {
                report.too_large += 1;
            }
        }
        Outcome::Panicked(message) => report.fail(FailureClass::Panic, message, input),
        Outcome::Hung => report.fail(
            FailureClass::Hang,
            format!("still running after {:?}", config.budget),
            input,
        ),
    }
}
