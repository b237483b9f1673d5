//! `rne eval MODEL --q ..`: the dynamics at one state, computed by one engine — the kernels
//! compiled in memory (`jit`, the default), the built-in robots' kernels compiled into rne
//! (`compiled`), the same programs evaluated operation by operation (`interpreted`), or the
//! independent numeric reference (`numeric`). With a floating base `--q` has NQ entries and
//! the others NV (docs/design.md §4.5).

use std::io::Write;

use clap::{Args, ValueEnum};

use super::eval_kernels::{self, Group, Names, State};
use super::model::ModelOptions;
use super::options::parse_list;
use super::CliError;
use rne_codegen::{Dynamics, Kernel, Shape};
use rne_codegen_core::{GenerationOptions, Scene};
use rne_interpreted::{evaluate, Interpreted, StateRef};
use rne_jit::{JitError, JitModel};
use rne_models::{RobotSource, Visitor};
use rne_reference::Reference;
use rne_symbolic::RobotModel;

/// Which implementation computes the numbers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Engine {
    /// The generated programs compiled in memory for this processor (Cranelift); the
    /// interpreter where the processor has no JIT.
    Jit,
    /// The built-in robots' kernels compiled into rne (robots as their files describe them).
    Compiled,
    /// The generated programs evaluated operation by operation.
    #[value(alias = "symbolic")]
    Interpreted,
    /// The independent numeric reference (spatial RNEA, CRBA, ABA).
    Numeric,
}

impl Engine {
    fn label(self) -> &'static str {
        match self {
            Engine::Jit => "jit",
            Engine::Compiled => "compiled",
            Engine::Interpreted => "interpreted",
            Engine::Numeric => "numeric",
        }
    }
}

/// What to print.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Quantity {
    /// Joint torques τ(q, q̇, q̈).
    Tau,
    /// Mass matrix M(q).
    #[value(name = "M")]
    M,
    /// Christoffel Coriolis matrix C(q, q̇).
    #[value(name = "C")]
    C,
    /// Gravity torques g(q).
    #[value(name = "g")]
    G,
    /// Bias C(q, q̇) q̇ + g(q).
    Bias,
    /// Forward dynamics q̈(q, q̇, τ).
    Fd,
    /// Kinetic and potential energy.
    Energy,
    /// The dynamics above: τ, M, C, g, the bias, q̈ and the energies (the default).
    Dynamics,
    /// ∂τ/∂q, ∂τ/∂q̇, ∂q̈/∂q, ∂q̈/∂q̇ and M⁻¹ (∂/∂q in the tangent space).
    Derivatives,
    /// Placements, Jacobians and J̇q̇ of every frame.
    Kinematics,
    /// The regressor and the base regressor, with the parameters' names.
    Regressor,
    /// Everything.
    All,
}

/// Arguments of `rne eval`.
#[derive(Debug, Args)]
pub struct EvalArgs {
    /// A built-in robot name or a path to a .toml spec or .urdf file.
    pub model: String,
    /// Model options.
    #[command(flatten)]
    pub options: ModelOptions,
    /// Configuration q, comma-separated (NQ values: a floating base's 7 first, its quaternion
    /// [qx, qy, qz, qw] of unit norm).
    #[arg(long, allow_hyphen_values = true)]
    pub q: String,
    /// Velocity v (NV values; default zero).
    #[arg(long, allow_hyphen_values = true)]
    pub qd: Option<String>,
    /// Acceleration (NV values; default zero).
    #[arg(long, allow_hyphen_values = true)]
    pub qdd: Option<String>,
    /// Generalised forces for forward dynamics (NV values; default zero).
    #[arg(long, allow_hyphen_values = true)]
    pub tau: Option<String>,
    /// What to compute, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "dynamics")]
    pub what: Vec<Quantity>,
    /// Which implementation computes it.
    #[arg(long, value_enum, default_value = "jit")]
    pub engine: Engine,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// The state given, checked: each array of its length and finite, a floating base's
/// quaternion of unit norm.
struct Given {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    tau: Vec<f64>,
}

impl Given {
    fn parse(args: &EvalArgs, model: &RobotModel) -> Result<Given, CliError> {
        let layout = model.state_layout();
        let array = |name: &str, text: Option<&String>, len: usize| -> Result<Vec<f64>, CliError> {
            let values = match text {
                Some(text) => parse_list(name, text)?,
                None => vec![0.0; len],
            };
            if values.len() != len {
                return Err(CliError::Argument(format!(
                    "--{name} has {} values; the robot needs {len}",
                    values.len()
                )));
            }
            if let Some(k) = values.iter().position(|x| !x.is_finite()) {
                return Err(CliError::Argument(format!(
                    "--{name}: entry {k} is {}; every value must be finite",
                    values[k]
                )));
            }
            Ok(values)
        };
        let given = Given {
            q: array("q", Some(&args.q), layout.nq())?,
            qd: array("qd", args.qd.as_ref(), layout.nv())?,
            qdd: array("qdd", args.qdd.as_ref(), layout.nv())?,
            tau: array("tau", args.tau.as_ref(), layout.nv())?,
        };
        if layout.floating {
            let norm = given.q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
            if (norm - 1.0).abs() > 1e-9 {
                return Err(CliError::Argument(format!(
                    "--q: the base quaternion [qx, qy, qz, qw] = {:?} has norm {norm}; it must \
                     be a unit quaternion (divide it by its norm)",
                    &given.q[3..7]
                )));
            }
        }
        Ok(given)
    }

    fn state(&self) -> StateRef<'_> {
        StateRef {
            q: &self.q,
            qd: &self.qd,
            qdd: &self.qdd,
            tau: &self.tau,
        }
    }
}

/// Computes the requested quantities and prints them.
pub fn run(args: &EvalArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(&args.model);
    let model = args.options.load(&source, false)?;
    let given = Given::parse(args, &model)?;
    // Forward dynamics of a model with a joint that moves no mass is undefined: an error when
    // asked for by name, left out (and said why) otherwise.
    let singular = model.check_mass_matrix_invertible().err();
    if let (Some(cause), true) = (&singular, args.what.contains(&Quantity::Fd)) {
        return Err(CliError::Massless {
            model: args.model.clone(),
            cause: cause.clone(),
        });
    }
    let wanted = Wanted::new(&args.what, singular.is_some());
    let (engine, mut results) = match args.engine {
        Engine::Numeric => (Engine::Numeric, numeric(&model, &wanted, &given, args)?),
        Engine::Compiled => (
            Engine::Compiled,
            compiled(&source, &model, &wanted, &given, args)?,
        ),
        Engine::Interpreted => (
            Engine::Interpreted,
            interpreted(&model, &wanted, &given, args)?,
        ),
        Engine::Jit => match jit(&model, &wanted, &given, args) {
            Err(CliError::Jit(JitError::UnsupportedHost(why))) => {
                eprintln!("warning: {why}; the interpreter computes instead");
                (
                    Engine::Interpreted,
                    interpreted(&model, &wanted, &given, args)?,
                )
            }
            other => (Engine::Jit, other?),
        },
    };
    if let Some(e) = &singular {
        results.push(("qdd_undefined", serde_json::json!(e.to_string())));
    }
    print(out, args, &source, &model, engine, results)
}

/// The kernels and groups asked for.
struct Wanted {
    kernels: Vec<Kernel>,
    groups: Vec<Group>,
}

impl Wanted {
    fn new(what: &[Quantity], singular: bool) -> Wanted {
        let asks = |q: Quantity| {
            what.contains(&q)
                || what.contains(&Quantity::All)
                || (what.contains(&Quantity::Dynamics) && DYNAMICS.contains(&q))
        };
        let kernels = KERNELS
            .iter()
            .filter(|(q, k)| asks(*q) && !(singular && k.inverts_mass_matrix()))
            .map(|&(_, k)| k)
            .collect();
        let groups = [
            (Quantity::Derivatives, Group::Derivatives),
            (Quantity::Kinematics, Group::Kinematics),
            (Quantity::Regressor, Group::Regressor),
        ]
        .into_iter()
        .filter(|&(q, g)| asks(q) && !(singular && g == Group::Derivatives))
        .map(|(_, g)| g)
        .collect();
        Wanted { kernels, groups }
    }

    /// Every kernel, the groups' included.
    fn all_kernels(&self) -> Vec<Kernel> {
        let mut all = self.kernels.clone();
        all.extend(self.groups.iter().flat_map(|g| g.kernels().iter().copied()));
        all
    }
}

/// The quantities of `Quantity::Dynamics`.
const DYNAMICS: [Quantity; 7] = [
    Quantity::Tau,
    Quantity::M,
    Quantity::C,
    Quantity::G,
    Quantity::Bias,
    Quantity::Fd,
    Quantity::Energy,
];

type Results = Vec<(&'static str, serde_json::Value)>;

/// The entries of one kernel's values.
fn entry(kernel: Kernel, values: Vec<f64>, nv: usize) -> (&'static str, serde_json::Value) {
    let value = match kernel.shape() {
        Shape::Matrix => serde_json::json!(values
            .chunks(nv.max(1))
            .map(<[f64]>::to_vec)
            .collect::<Vec<_>>()),
        Shape::Scalar => serde_json::json!(values.first().copied().unwrap_or(f64::NAN)),
        _ => serde_json::json!(values),
    };
    (key(kernel), value)
}

/// By the kernels compiled in memory: the kernels asked for and their groups', at once.
fn jit(
    model: &RobotModel,
    wanted: &Wanted,
    given: &Given,
    args: &EvalArgs,
) -> Result<Results, CliError> {
    let options = GenerationOptions {
        outputs: wanted.all_kernels(),
        ..GenerationOptions::default()
    };
    let jit = JitModel::compile(model, &args.options.scene(), &options, &args.model)?;
    let s = given.state();
    let state = rne_jit::State {
        q: s.q,
        qd: s.qd,
        qdd: s.qdd,
        tau: s.tau,
    };
    let mut results: Results = Vec::new();
    for &kernel in &wanted.kernels {
        results.push(entry(kernel, jit.evaluate_vec(kernel, state)?, jit.nv()));
    }
    let names = Names {
        frames: jit.frames(),
        parameters: jit.parameter_names(),
        base_parameters: jit.base_parameter_names(),
        nv: jit.nv(),
    };
    let mut eval = |kernel| Ok(jit.evaluate_vec(kernel, state)?);
    for &group in &wanted.groups {
        results.extend(eval_kernels::entries(group, &names, &mut eval)?);
    }
    Ok(results)
}

/// By the programs evaluated operation by operation.
fn interpreted(
    model: &RobotModel,
    wanted: &Wanted,
    given: &Given,
    args: &EvalArgs,
) -> Result<Results, CliError> {
    let programs = Interpreted::with_kernels(model, &wanted.kernels);
    let mut results: Results = Vec::new();
    for &kernel in &wanted.kernels {
        let values = programs.evaluate(kernel, given.state())?;
        results.push(entry(kernel, values, programs.nv()));
    }
    results.extend(groups(model, wanted, given, args, eval_kernels::symbolic)?);
    Ok(results)
}

/// By the built-in robot's compiled module: the dynamics kernels of a robot as its file
/// describes it.
fn compiled(
    source: &RobotSource,
    model: &RobotModel,
    wanted: &Wanted,
    given: &Given,
    args: &EvalArgs,
) -> Result<Results, CliError> {
    let robot = match source {
        RobotSource::Builtin(robot) if args.options.keeps_the_file_model() => robot,
        _ => {
            return Err(CliError::Argument(format!(
                "`{}`: the compiled kernels are the built-in robots' as their files describe \
                 them (see `rne models`); use --engine jit",
                args.model
            )))
        }
    };
    if !wanted.groups.is_empty() {
        return Err(CliError::Argument(
            "the built-in robots' compiled modules have the dynamics kernels; use --engine \
             jit for derivatives, kinematics and regressors"
                .into(),
        ));
    }
    let values = robot.visit(Values {
        kernels: &wanted.kernels,
        state: given.state(),
    })?;
    let nv = model.state_layout().nv();
    Ok(values.into_iter().map(|(k, v)| entry(k, v, nv)).collect())
}

/// By the independent numeric reference.
fn numeric(
    model: &RobotModel,
    wanted: &Wanted,
    given: &Given,
    args: &EvalArgs,
) -> Result<Results, CliError> {
    if wanted.kernels.contains(&Kernel::CoriolisMatrix) && args.what.contains(&Quantity::C) {
        return Err(CliError::Argument(
            "the numeric reference computes C(q, q̇) q̇ (see `bias`), not the Christoffel \
             matrix; use --engine jit"
                .into(),
        ));
    }
    let mut reference = Reference::try_new(&model.to_numeric())?;
    let (q, qd, qdd, tau) = (&given.q, &given.qd, &given.qdd, &given.tau);
    let nv = model.state_layout().nv();
    let rows = |m: nalgebra::DMatrix<f64>| -> Vec<f64> { m.transpose().as_slice().to_vec() };
    let mut results: Results = Vec::new();
    for &kernel in &wanted.kernels {
        let values = match kernel {
            Kernel::InverseDynamics => reference.inverse_dynamics(q, qd, qdd)?.data.into(),
            Kernel::MassMatrix => rows(reference.mass_matrix(q)?),
            Kernel::GravityTorques => reference.gravity_torques(q)?.data.into(),
            Kernel::BiasTorques => reference.bias_torques(q, qd)?.data.into(),
            Kernel::ForwardDynamics => reference.forward_dynamics(q, qd, tau)?.data.into(),
            Kernel::KineticEnergy => vec![reference.kinetic_energy(q, qd)?],
            Kernel::PotentialEnergy => vec![reference.potential_energy(q)?],
            _ => continue,
        };
        results.push(entry(kernel, values, nv));
    }
    results.extend(groups(model, wanted, given, args, eval_kernels::numeric)?);
    Ok(results)
}

/// The groups' entries by `engine` (an `eval_kernels` function).
fn groups(
    model: &RobotModel,
    wanted: &Wanted,
    given: &Given,
    args: &EvalArgs,
    engine: fn(&RobotModel, &Scene, Group, &State) -> Result<Results, CliError>,
) -> Result<Results, CliError> {
    let at = State {
        q: &given.q,
        qd: &given.qd,
        qdd: &given.qdd,
        tau: &given.tau,
    };
    let mut results = Results::new();
    for &group in &wanted.groups {
        results.extend(engine(model, &args.options.scene(), group, &at)?);
    }
    Ok(results)
}

/// The kernels behind each quantity, in output order.
const KERNELS: [(Quantity, Kernel); 8] = [
    (Quantity::Tau, Kernel::InverseDynamics),
    (Quantity::M, Kernel::MassMatrix),
    (Quantity::C, Kernel::CoriolisMatrix),
    (Quantity::G, Kernel::GravityTorques),
    (Quantity::Bias, Kernel::BiasTorques),
    (Quantity::Fd, Kernel::ForwardDynamics),
    (Quantity::Energy, Kernel::KineticEnergy),
    (Quantity::Energy, Kernel::PotentialEnergy),
];

/// The output key of a kernel's value.
fn key(kernel: Kernel) -> &'static str {
    match kernel {
        Kernel::InverseDynamics => "tau",
        Kernel::MassMatrix => "M",
        Kernel::CoriolisMatrix => "C",
        Kernel::GravityTorques => "g",
        Kernel::BiasTorques => "bias",
        Kernel::ForwardDynamics => "qdd",
        Kernel::KineticEnergy => "kinetic",
        Kernel::PotentialEnergy => "potential",
        other => other.name(),
    }
}

/// The values of `kernels` of a built-in robot's generated `Model` at `state`.
struct Values<'a> {
    kernels: &'a [Kernel],
    state: StateRef<'a>,
}

impl Visitor for Values<'_> {
    type Output = Result<Vec<(Kernel, Vec<f64>)>, rne_interpreted::Error>;

    fn visit<const N: usize, D: Dynamics<N, N, Scalar = f64>>(self, model: D) -> Self::Output {
        self.kernels
            .iter()
            .map(|&k| Ok((k, evaluate(&model, k, self.state)?)))
            .collect()
    }
}

/// Prints the results: one JSON object, or a header naming the model and the engine and each
/// quantity with its numbers in shortest round-trip form, matrices in aligned columns.
fn print(
    out: &mut dyn Write,
    args: &EvalArgs,
    source: &RobotSource,
    model: &RobotModel,
    engine: Engine,
    results: Results,
) -> Result<(), CliError> {
    if args.json {
        let mut object = serde_json::Map::new();
        object.insert("model".into(), serde_json::json!(source.display_name()));
        object.insert("engine".into(), serde_json::json!(engine.label()));
        object.insert("joints".into(), serde_json::json!(model.joint_names()));
        for (key, value) in results {
            object.insert(key.into(), value);
        }
        writeln!(out, "{}", serde_json::Value::Object(object))?;
        return Ok(());
    }
    writeln!(out, "model: {}", source.display_name())?;
    writeln!(out, "engine: {}", engine.label())?;
    writeln!(out, "joints: {}", model.joint_names().join(", "))?;
    for (key, value) in results {
        match value {
            serde_json::Value::Array(rows) if rows.first().is_some_and(|r| r.is_array()) => {
                writeln!(out, "{key}:")?;
                for line in aligned(&rows) {
                    writeln!(out, "  {line}")?;
                }
            }
            other => writeln!(out, "{key}: {}", text(&other))?,
        }
    }
    Ok(())
}

/// A value's text: numbers in their shortest round-trip form, arrays in brackets.
fn text(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::Array(items) => {
            let items: Vec<String> = items.iter().map(text).collect();
            format!("[{}]", items.join(", "))
        }
        serde_json::Value::Number(n) => n
            .as_f64()
            .map_or_else(|| n.to_string(), |x| format!("{x:?}")),
        other => other.to_string(),
    }
}

/// Rows of a matrix with each column right-aligned to its widest entry (rows of other shapes
/// as they are).
fn aligned(rows: &[serde_json::Value]) -> Vec<String> {
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|row| match row {
            serde_json::Value::Array(items) => items.iter().map(text).collect(),
            other => vec![text(other)],
        })
        .collect();
    let columns = cells.iter().map(Vec::len).max().unwrap_or(0);
    let widths: Vec<usize> = (0..columns)
        .map(|c| {
            cells
                .iter()
                .filter_map(|r| r.get(c))
                .map(String::len)
                .max()
                .unwrap_or(0)
        })
        .collect();
    cells
        .iter()
        .map(|row| {
            let padded: Vec<String> = row
                .iter()
                .zip(&widths)
                .map(|(cell, &w)| format!("{cell:>w$}"))
                .collect();
            format!("[{}]", padded.join("  "))
        })
        .collect()
}
