//! `rne eval MODEL --q ..`: the dynamics at one state, from the generated kernels (built-in
//! robots as their files describe them), the expression graph (other files, other bases or
//! mimic modes) or the independent numeric reference. With a floating base `--q` has NQ
//! entries and the others NV (docs/design.md §4.5).

use std::io::Write;

use clap::{Args, ValueEnum};

use super::eval_kernels::{self, Group, State};
use super::model::ModelOptions;
use super::options::parse_list;
use super::CliError;
use rne_codegen::{Dynamics, Kernel, Shape};
use rne_interpreted::{evaluate, Interpreted, StateRef};
use rne_models::{RobotSource, Visitor};
use rne_reference::Reference;

/// Which implementation computes the numbers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Engine {
    /// Generated kernels for built-in robots; the expression graph for other files.
    Symbolic,
    /// The independent numeric reference (spatial RNEA, CRBA, ABA).
    Numeric,
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
    /// Configuration q, comma-separated (NQ values: a floating base's 7 first).
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
    #[arg(long, value_delimiter = ',', default_value = "all")]
    pub what: Vec<Quantity>,
    /// Which implementation computes it.
    #[arg(long, value_enum, default_value = "symbolic")]
    pub engine: Engine,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// Computes the requested quantities and prints them.
pub fn run(args: &EvalArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let source = RobotSource::resolve(&args.model);
    let model = args.options.load(&source, false)?;
    let nv = model.state_layout().nv();
    let q = parse_list("q", &args.q)?;
    let state = |name: &str, text: &Option<String>| match text {
        Some(text) => parse_list(name, text),
        None => Ok(vec![0.0; nv]),
    };
    let (qd, qdd, tau) = (
        state("qd", &args.qd)?,
        state("qdd", &args.qdd)?,
        state("tau", &args.tau)?,
    );
    // Forward dynamics of a model with a joint that moves no mass is undefined: an error when
    // asked for by name, left out (and said why) from `all`.
    let singular = model.check_mass_matrix_invertible().err();
    if let (Some(e), true) = (&singular, args.what.contains(&Quantity::Fd)) {
        return Err(CliError::Argument(format!("{}: {e}", args.model)));
    }
    let wants = |q: Quantity| {
        (args.what.contains(&q) || args.what.contains(&Quantity::All))
            && !(q == Quantity::Fd && singular.is_some())
    };

    let mut results: Vec<(&str, serde_json::Value)> = Vec::new();
    let vector = |v: Vec<f64>| serde_json::json!(v);
    let matrix = |m: Vec<Vec<f64>>| serde_json::json!(m);
    match args.engine {
        Engine::Symbolic => {
            let kernels: Vec<Kernel> = KERNELS
                .iter()
                .filter(|(quantity, _)| wants(*quantity))
                .map(|&(_, kernel)| kernel)
                .collect();
            let state = StateRef {
                q: &q,
                qd: &qd,
                qdd: &qdd,
                tau: &tau,
            };
            let values = match &source {
                RobotSource::Builtin(robot) if args.options.keeps_the_file_model() => {
                    robot.visit(Values {
                        kernels: &kernels,
                        state,
                    })?
                }
                _ => {
                    let programs = Interpreted::new(&model);
                    kernels
                        .iter()
                        .map(|&k| Ok((k, programs.evaluate(k, state)?)))
                        .collect::<Result<_, rne_interpreted::Error>>()?
                }
            };
            for (kernel, v) in values {
                let value = match kernel.shape() {
                    Shape::Matrix => matrix(v.chunks(nv.max(1)).map(<[f64]>::to_vec).collect()),
                    Shape::Scalar => serde_json::json!(v.first().copied().unwrap_or(f64::NAN)),
                    _ => vector(v),
                };
                results.push((key(kernel), value));
            }
        }
        Engine::Numeric => {
            let mut reference = Reference::try_new(&model.to_numeric())?;
            let rows = |m: nalgebra::DMatrix<f64>| -> Vec<Vec<f64>> {
                m.row_iter().map(|r| r.iter().copied().collect()).collect()
            };
            if wants(Quantity::Tau) {
                results.push((
                    "tau",
                    vector(reference.inverse_dynamics(&q, &qd, &qdd)?.data.into()),
                ));
            }
            if wants(Quantity::M) {
                results.push(("M", matrix(rows(reference.mass_matrix(&q)?))));
            }
            if args.what.contains(&Quantity::C) {
                return Err(CliError::Argument(
                    "the numeric reference computes C(q, q̇) q̇ (see `bias`), not the Christoffel matrix; use --engine symbolic".into(),
                ));
            }
            if wants(Quantity::G) {
                results.push(("g", vector(reference.gravity_torques(&q)?.data.into())));
            }
            if wants(Quantity::Bias) {
                results.push(("bias", vector(reference.bias_torques(&q, &qd)?.data.into())));
            }
            if wants(Quantity::Fd) {
                results.push((
                    "qdd",
                    vector(reference.forward_dynamics(&q, &qd, &tau)?.data.into()),
                ));
            }
            if wants(Quantity::Energy) {
                results.push((
                    "kinetic",
                    serde_json::json!(reference.kinetic_energy(&q, &qd)?),
                ));
                results.push((
                    "potential",
                    serde_json::json!(reference.potential_energy(&q)?),
                ));
            }
        }
    }

    let groups = [
        (Quantity::Derivatives, Group::Derivatives),
        (Quantity::Kinematics, Group::Kinematics),
        (Quantity::Regressor, Group::Regressor),
    ];
    let at = State {
        q: &q,
        qd: &qd,
        qdd: &qdd,
        tau: &tau,
    };
    for (quantity, group) in groups {
        if !wants(quantity) || (group == Group::Derivatives && singular.is_some()) {
            continue;
        }
        results.extend(match args.engine {
            Engine::Symbolic => eval_kernels::symbolic(&model, &args.options.scene(), group, &at)?,
            Engine::Numeric => eval_kernels::numeric(&model, &args.options.scene(), group, &at)?,
        });
    }
    if let Some(e) = &singular {
        results.push(("qdd_undefined", serde_json::json!(e.to_string())));
    }
    if args.json {
        let mut object = serde_json::Map::new();
        object.insert("model".into(), serde_json::json!(source.display_name()));
        object.insert("joints".into(), serde_json::json!(model.joint_names()));
        for (key, value) in results {
            object.insert(key.into(), value);
        }
        writeln!(out, "{}", serde_json::Value::Object(object))?;
    } else {
        writeln!(out, "model: {}", source.display_name())?;
        writeln!(out, "joints: {}", model.joint_names().join(", "))?;
        for (key, value) in results {
            match value {
                serde_json::Value::Array(rows) if rows.first().is_some_and(|r| r.is_array()) => {
                    writeln!(out, "{key}:")?;
                    for row in rows {
                        writeln!(out, "  {}", format_row(&row))?;
                    }
                }
                other => writeln!(out, "{key}: {}", format_row(&other))?,
            }
        }
    }
    Ok(())
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

fn format_row(value: &serde_json::Value) -> String {
    match value {
        serde_json::Value::Array(items) => {
            let items: Vec<String> = items.iter().map(format_row).collect();
            format!("[{}]", items.join(", "))
        }
        serde_json::Value::Number(n) => n
            .as_f64()
            .map_or_else(|| n.to_string(), |x| format!("{x:.17e}")),
        other => other.to_string(),
    }
}
