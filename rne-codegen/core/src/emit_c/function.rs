//! One kernel as a C function: its documented declaration and its definition, one statement
//! per instruction of its program (module `body`), cut into parts above [`SPLIT_ABOVE`]
//! instructions (module `parts`).

use std::collections::BTreeSet;
use std::fmt::Write;

use rne_symbolic::Symbol;

use super::body::Body;
use super::parts;
use super::text::c_comment;
use super::TEXT;
use crate::error::CodegenError;
use crate::generation_options::ParameterMode;
use crate::kernel::{Input, Kernel, Shape};
use crate::program::{Instr, Operand, Program};
use crate::programs::GeneratedPrograms;
use crate::split::plan_parts;

/// Programs with more instructions than this are written as a chain of functions of
/// [`PART_LEN`] instructions each. GCC 12 takes time that grows faster than linearly with a
/// function's length (`-ftime-report`: mostly "LRA hard reg assignment"): at `-O2`, the
/// Panda's `forward_dynamics_derivatives` (11 906 instructions) took 11.2 s of CPU as one
/// function, 9.0 s in parts of 4 000 instructions, 6.7 s of 2 000, 4.2 s of 1 000, 3.5 s of
/// 500 and 4.1 s of 250; its time per call, and that of `inverse_dynamics_derivatives`
/// (7 186), did not change measurably, split or not (within the ±15 % noise of a shared
/// machine). In parts of 500, GCC compiles the eight dynamics kernels of Talos (NV 38) in
/// 36 s and of G1 with hands (NV 49) in 47 s of CPU at `-O2`.
pub(super) const SPLIT_ABOVE: usize = 3000;

/// Instructions per part of a split kernel.
pub(super) const PART_LEN: usize = 500;

/// A kernel's C.
pub(super) struct Function {
    /// Its documentation and prototype, for the header.
    pub declaration: String,
    /// Its definition, for the source.
    pub definition: String,
}

/// An array the function writes its results to: its name, length and what it holds.
struct OutArray {
    name: &'static str,
    len: usize,
    doc: String,
}

/// Writes `kernel`, computing `program`, as the C function `<prefix>_<kernel>` of `module`;
/// `fields` names the runtime parameters' struct fields by symbol index.
pub(super) fn emit(
    prefix: &str,
    kernel: Kernel,
    program: &Program,
    module: &GeneratedPrograms,
    fields: &[String],
) -> Result<Function, CodegenError> {
    let error = |reason: String| CodegenError::CKernel { kernel, reason };
    let outs = out_arrays(prefix, kernel, module).map_err(error)?;
    if let Some(empty) = outs.iter().find(|a| a.len == 0) {
        return Err(error(format!("its result `{}` would be empty", empty.name)));
    }
    let expected = outs.iter().map(|a| a.len).sum::<usize>().max(1);
    if program.outputs.len() != expected {
        return Err(error(format!(
            "its program has {} outputs for a result of {expected} numbers",
            program.outputs.len()
        )));
    }
    let reads = symbols_read(program).map_err(error)?;
    let signature = Signature::new(prefix, kernel, module, &outs);
    let declaration = format!(
        "{}{};\n",
        signature.doc(prefix, kernel, module, &outs),
        signature.prototype
    );
    let body = Body::new(kernel, program, fields, signature.takes_params);
    let places = places(&outs);
    let mut definition = String::with_capacity(40 * program.instrs.len() + 1024);
    if program.instrs.len() > SPLIT_ABOVE {
        write_parts(prefix, kernel, &body, &signature, &places, &mut definition);
    } else {
        definition.push_str(&signature.prototype);
        definition.push_str(" {\n");
        body.write_whole(&reads, &places, &mut definition);
        definition.push_str("}\n");
    }
    Ok(Function {
        declaration,
        definition,
    })
}

/// The kernel as parts of [`PART_LEN`] instructions and the function calling them.
fn write_parts(
    prefix: &str,
    kernel: Kernel,
    body: &Body,
    signature: &Signature,
    places: &[(&str, usize)],
    out: &mut String,
) {
    let prologue = body.prologue_flags();
    let named: Vec<bool> = prologue.iter().map(|&p| !p).collect();
    let plan = plan_parts(body.program, &named, &prologue, PART_LEN);
    let head = parts::Head {
        name: format!("{prefix}_{}", kernel.name()),
        parameters: signature.inputs.clone(),
        arguments: signature.arguments.clone(),
    };
    parts::write(body, &plan, &head, places, &signature.prototype, out);
}

/// Every input symbol the program reads, ordered; an error for a vector lane.
fn symbols_read(program: &Program) -> Result<BTreeSet<Symbol>, String> {
    let mut reads = BTreeSet::new();
    let operands = program
        .instrs
        .iter()
        .flat_map(Instr::operands)
        .chain(program.outputs.iter().copied());
    for operand in operands {
        match operand {
            Operand::Input(Symbol::Lane(_)) | Operand::Lane { .. } => {
                return Err("it computes with vector lanes, which C kernels do not have (build it in scalars)".to_owned());
            }
            Operand::Input(symbol) => {
                reads.insert(symbol);
            }
            Operand::Temp(_) | Operand::Const(_) => {}
        }
    }
    Ok(reads)
}

/// The arrays `kernel` writes (none for a scalar, which it returns), in output order; an error
/// for a shape C has no layout for.
fn out_arrays(
    prefix: &str,
    kernel: Kernel,
    module: &GeneratedPrograms,
) -> Result<Vec<OutArray>, String> {
    let (nv, nf, np, nb) = (
        module.dims.nv,
        module.dims.nf,
        module.dims.np,
        module.dims.nb,
    );
    let out = |len: usize, doc: String| {
        vec![OutArray {
            name: "out",
            len,
            doc,
        }]
    };
    let square = |name: &'static str, what: &str| OutArray {
        name,
        len: nv * nv,
        doc: format!("{what}, row-major: {name}[{nv}*i + j] is row i, column j."),
    };
    Ok(match kernel.shape() {
        Shape::Scalar => Vec::new(),
        Shape::Vector => out(nv, format!("the {nv} values, in the order of qd.")),
        Shape::Matrix => out(nv * nv, format!("row-major: out[{nv}*i + j] is row i, column j.")),
        Shape::Matrices(_) if kernel == Kernel::InverseDynamicsDerivatives => vec![
            square("dtau_dq", "the derivatives of tau with respect to q (tangent space)"),
            square("dtau_dqd", "the derivatives of tau with respect to qd"),
        ],
        Shape::Matrices(_) => vec![
            square("dqdd_dq", "the derivatives of qdd with respect to q (tangent space)"),
            square("dqdd_dqd", "the derivatives of qdd with respect to qd"),
            square("minv", "the inverse mass matrix, the derivatives of qdd with respect to tau"),
        ],
        Shape::Placements => out(
            12 * nf,
            format!("per frame f ({prefix}_frame_names[f]), its rotation row-major in out[12*f] .. out[12*f + 8] and its origin in out[12*f + 9] .. out[12*f + 11]."),
        ),
        Shape::FrameMatrices => out(
            6 * nv * nf,
            format!("per frame f ({prefix}_frame_names[f]), its 6 x {nv} Jacobian (rows: linear then angular velocity) row-major from out[{}*f]: out[{}*f + {nv}*i + j].", 6 * nv, 6 * nv),
        ),
        Shape::FrameVectors => out(
            6 * nf,
            format!("per frame f ({prefix}_frame_names[f]), J-dot qd (linear then angular) in out[6*f] .. out[6*f + 5]."),
        ),
        Shape::Regressor => out(
            nv * np,
            format!("row-major {nv} x {np}: out[{np}*i + j] is row i, column j the parameter {prefix}_parameter_names[j]."),
        ),
        Shape::BaseRegressor => out(
            nv * nb,
            format!("row-major {nv} x {nb}: out[{nb}*i + j] is row i, column j the parameter {prefix}_base_parameter_names[j]."),
        ),
        Shape::BaseVector => out(nb, format!("the {nb} base parameters, in the order of {prefix}_base_parameter_names.")),
        other => return Err(format!("C has no layout for its shape {other:?}")),
    })
}

/// A function's parameters and prototype.
struct Signature {
    /// `void ur5_mass_matrix(const double q[6], double out[36])`.
    prototype: String,
    /// Whether it takes the runtime parameters `p`.
    takes_params: bool,
    /// The parameters before the results: `const double q[6]`.
    inputs: Vec<String>,
    /// Their names, as a call passes them on: `q`.
    arguments: Vec<&'static str>,
}

impl Signature {
    fn new(
        prefix: &str,
        kernel: Kernel,
        module: &GeneratedPrograms,
        outs: &[OutArray],
    ) -> Signature {
        let takes_params = module.parameter_mode != ParameterMode::Constant;
        let mut inputs: Vec<String> = Vec::new();
        let mut arguments: Vec<&'static str> = Vec::new();
        if takes_params {
            inputs.push(format!("const struct {prefix}_params *p"));
            arguments.push("p");
        }
        for &input in kernel.inputs() {
            inputs.push(format!(
                "const double {}[{}]",
                input.name(),
                input_len(input, module)
            ));
            arguments.push(input.name());
        }
        let results = outs
            .iter()
            .map(|out| format!("double {}[{}]", out.name, out.len));
        let parameters: Vec<String> = inputs.iter().cloned().chain(results).collect();
        let returns = if outs.is_empty() { "double" } else { "void" };
        Signature {
            prototype: format!(
                "{returns} {prefix}_{}({})",
                kernel.name(),
                parameters.join(", ")
            ),
            takes_params,
            inputs,
            arguments,
        }
    }

    /// The declaration's documentation: what it computes, then each array.
    fn doc(
        &self,
        prefix: &str,
        kernel: Kernel,
        module: &GeneratedPrograms,
        outs: &[OutArray],
    ) -> String {
        // The Rust module's names of the sizes and name arrays, as the header names them.
        let summary = kernel
            .summary()
            .replace("`PARAMETERS`", &format!("{prefix}_parameter_names"))
            .replace(
                "`BASE_PARAMETERS`",
                &format!("{prefix}_base_parameter_names"),
            )
            .replace("`FRAMES`", &format!("{prefix}_frame_names"));
        let mut doc = format!("{summary}\n\n");
        if self.takes_params {
            writeln!(
                doc,
                "p: the parameters read at run time (struct {prefix}_params)."
            )
            .expect(TEXT);
        }
        for &input in kernel.inputs() {
            let what = match input {
                Input::Q => "joint positions".to_owned(),
                Input::Qd => "joint velocities".to_owned(),
                Input::Qdd => "joint accelerations".to_owned(),
                Input::Tau => "generalised forces".to_owned(),
                Input::Standard => {
                    format!("standard parameters, in the order of {prefix}_parameter_names")
                }
            };
            writeln!(
                doc,
                "{}: {what} ({}).",
                input.name(),
                input_len(input, module)
            )
            .expect(TEXT);
        }
        for out in outs {
            writeln!(doc, "{}: {}", out.name, out.doc).expect(TEXT);
        }
        if outs.is_empty() {
            doc.push_str("Returns the value.\n");
        }
        c_comment(&doc, true)
    }
}

/// The length of the array `input`.
fn input_len(input: Input, module: &GeneratedPrograms) -> usize {
    match input {
        Input::Q => module.nq,
        Input::Standard => module.dims.np,
        Input::Qd | Input::Qdd | Input::Tau => module.dims.nv,
    }
}

/// Where each output goes: (array, index), in output order; empty for a scalar, which is
/// returned.
fn places(outs: &[OutArray]) -> Vec<(&'static str, usize)> {
    outs.iter()
        .flat_map(|a| (0..a.len).map(move |i| (a.name, i)))
        .collect()
}
