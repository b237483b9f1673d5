//! Emission of a module's kernels as C99 for C and C++ programs: a header and a source file
//! per robot ([`generate_c`], `rne emit --lang c`).
//!
//! The kernels are the programs [`generate`](crate::generate) emits as Rust
//! ([`generate_programs`]), written as one `const double tN = …;` statement per instruction in
//! program order: nothing is re-associated, and each operation is the program's. The sine and
//! cosine are the Rust runtime's `sin_cos`, ported to C operation for operation
//! (`emit_c/trig.c`); `sign` is the runtime's (`x` itself for ±0 and NaN); the fused
//! multiply-adds of `fma: true` and of the sine and cosine go through `fma()` exactly where
//! the runtime's `mul_add` is fused (x86-64 with FMA). So, compiled as documented in the
//! header (IEEE double arithmetic without excess precision, as on x86-64; no contraction of
//! products and sums, which the source asks GCC and Clang for itself, with GCC's vectorizer
//! off, since GCC 12's fuses a product and a sum into `vfmaddsub` even with
//! `-ffp-contract=off`; `-mfma` exactly when
//! the Rust build has the `fma` target feature; no `-ffast-math`), the C kernels return the
//! Rust kernels' results bit for bit. The derivative kernels are built in scalars: C has no
//! lanes (`derivatives: lanes` is ignored).
//!
//! The functions are named `<robot>_<kernel>`, `<robot>` the robot's name as a C identifier
//! ([`c_identifier`]); they take `const double` arrays of documented sizes and write their
//! results to `double` arrays (a scalar is returned), matrices row-major, each matrix of a
//! tuple to an array of its own. Inputs are read into locals before any result is written,
//! so an output array may even be an input array. With runtime parameters the functions
//! take a `const struct <robot>_params *` first.
//!
//! The output depends on the programs alone: the same robot and scene give the same bytes.

mod body;
mod function;
mod parts;
mod text;

use std::fmt::Write;

use rne_symbolic::model::Parameter;
use rne_symbolic::RobotModel;

use crate::error::CodegenError;
use crate::generation_options::{GenerationOptions, ParameterMode, ScalarType};
use crate::program::{Instr, Operand};
use crate::programs::{generate_programs, GeneratedPrograms, KernelProgram};
use crate::scene::Scene;

pub use text::c_identifier;
use text::{c_comment, c_double, c_string, is_c_identifier};

/// What writing to a `String` cannot fail at.
const TEXT: &str = "writing to a String";

/// The runtime's sine and cosine in C (`emit_c/trig.c`), after [`MUL_ADD`].
const TRIG: &str = include_str!("emit_c/trig.c");

/// `rne_mul_add`, fused exactly where the Rust runtime's `mul_add` is.
const MUL_ADD: &str = "\
/* x * y + z: rounded once, by fma(), where the Rust runtime's Real::mul_add is fused (x86-64
 * with FMA: -mfma, or -march= a processor with it), else a product and a sum, each rounded. */
static double rne_mul_add(double x, double y, double z) {
#if defined(__x86_64__) && defined(__FMA__)
    return fma(x, y, z);
#else
    return x * y + z;
#endif
}
";

/// `rne_sign`, the runtime's `sign_of`.
const SIGN: &str = "\
/* 1 for positive x, -1 for negative x, x itself for +0, -0 and NaN (the runtime's sign). */
static double rne_sign(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : x; }
";

/// `rne_sin`, for a sine of something other than a joint angle.
const SIN: &str = "\
/* sin x (rne_sin_cos). */
static double rne_sin(double x) {
    double s, c;
    rne_sin_cos(x, &s, &c);
    return s;
}
";

/// `rne_cos`, for a cosine of something other than a joint angle.
const COS: &str = "\
/* cos x (rne_sin_cos). */
static double rne_cos(double x) {
    double s, c;
    rne_sin_cos(x, &s, &c);
    return c;
}
";

/// How to compile the C for the Rust kernels' results, written at the top of both files.
const FLAGS: &str = "\
Compile as C99 or later, or as C++ (the header has extern \"C\" guards); nothing beyond
<math.h> is needed (fma() and sqrt(), which GCC and Clang inline on x86-64; with other
compilers, or for a kernel with a square root without -fno-math-errno, link with -lm).

Bit for bit the Rust kernels of the same robot and scene: on a target with IEEE double
arithmetic and no excess precision (FLT_EVAL_METHOD 0: x86-64, AArch64), without
-ffast-math, with products and sums never contracted into fused multiply-adds (the source
turns contraction, and GCC's vectorizer, which contracts even so, off for GCC and Clang
itself; elsewhere compile with -ffp-contract=off -fno-tree-vectorize or their equivalent),
and with -mfma (or a -march= with FMA) exactly when the Rust build has the
`fma` target feature (-C target-feature=+fma, or -C target-cpu=native on such a processor):
the runtime's fused multiply-adds, and this file's rne_mul_add, are fused exactly there.
For example: cc -std=c99 -O2 -c robot.c (Rust built for baseline x86-64), or
cc -std=c99 -O3 -march=native -c robot.c (Rust built with -C target-cpu=native).";

/// A module's C: a header and a source file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CModule {
    /// The C identifier every name starts with (the robot's name, [`c_identifier`]), and the
    /// files' stem: `<name>.h` and `<name>.c`.
    pub name: String,
    /// The header: sizes, names, the parameters' struct and one declaration per kernel.
    pub header: String,
    /// The source: the kernels' definitions, with the runtime's functions they need.
    pub source: String,
}

/// Generates the C of the kernels `options` ask for, for `model` in `scene` (`model` loaded
/// with symbolic parameters when the options want runtime parameters): [`generate_programs`],
/// then [`emit_c`]. `source` names the robot file in the files' comments and in errors. The
/// options' scalar must be `f64`.
pub fn generate_c(
    model: &RobotModel,
    scene: &Scene,
    options: &GenerationOptions,
    source: &str,
) -> Result<CModule, CodegenError> {
    if options.scalar != ScalarType::F64 {
        return Err(CodegenError::CEmission(format!(
            "C kernels compute in double; the options ask for {:?} scalars",
            options.scalar
        )));
    }
    emit_c(&generate_programs(model, scene, options, source)?, source)
}

/// Writes `module`'s kernels as C. An error names a kernel that cannot be written (one that
/// reads vector lanes, or whose result is empty) or a parameter whose name is no C
/// identifier.
pub fn emit_c(module: &GeneratedPrograms, source: &str) -> Result<CModule, CodegenError> {
    let name = c_identifier(&module.robot);
    let fields = parameter_fields(module)?;
    let mut declarations = String::new();
    let mut definitions = String::new();
    for KernelProgram {
        kernel, program, ..
    } in &module.kernels
    {
        let function = function::emit(&name, *kernel, program, module, &fields)?;
        declarations.push('\n');
        declarations.push_str(&function.declaration);
        definitions.push('\n');
        definitions.push_str(&function.definition);
    }
    let header = header(&name, module, source, &declarations);
    let mut c = String::with_capacity(definitions.len() + TRIG.len() + 4096);
    c.push_str(&c_comment(&format!(
        "Dynamics of `{}`, generated by rne from `{source}`: the definitions of {name}.h.\n\n{FLAGS}",
        module.robot
    ), false));
    write!(
        c,
        "\n#include \"{name}.h\"\n\n#include <math.h>\n#include <stdint.h>\n#include <string.h>\n\n\
         /* No contraction of products and sums into fused multiply-adds: the kernels compute\n \
         * exactly the operations written. GCC's vectorizer fuses them even so (GCC 12 with FMA\n \
         * makes vfmaddsub of a product and a sum or difference beside it, with\n \
         * -ffp-contract=off too), so it is turned off as well; the kernels have no loops, and\n \
         * were no slower without it. */\n\
         #if defined(__clang__)\n#pragma STDC FP_CONTRACT OFF\n\
         #elif defined(__GNUC__)\n#pragma GCC optimize(\"fp-contract=off\", \"no-tree-vectorize\")\n#endif\n"
    )
    .expect(TEXT);
    c.push_str(&name_definitions(&name, module));
    c.push_str(&params_definitions(&name, module));
    c.push_str(&helpers(module));
    c.push_str(&definitions);
    Ok(CModule {
        name,
        header,
        source: c,
    })
}

/// The header: the flags, the sizes, the names, the parameters' struct and the declarations.
fn header(name: &str, module: &GeneratedPrograms, source: &str, declarations: &str) -> String {
    let upper = name.to_ascii_uppercase();
    let mut h = c_comment(
        &format!(
            "Dynamics of `{}`, generated by rne from `{source}`.\n\n\
         Arrays are of double; matrices are row-major. {state}\n\n{FLAGS}",
            module.robot,
            state = state_doc(module),
        ),
        false,
    );
    write!(
        h,
        "\n#ifndef {upper}_H\n#define {upper}_H\n\n#ifdef __cplusplus\nextern \"C\" {{\n#endif\n\n"
    )
    .expect(TEXT);
    let sizes = [
        ("NDOF", module.ndof, "Number of joint variables.", true),
        ("NQ", module.nq, "Size of q.", true),
        ("NV", module.dims.nv, "Size of qd, qdd and tau.", true),
        (
            "NF",
            module.dims.nf,
            "Number of frames of the kinematics functions.",
            names_frames(module),
        ),
        (
            "NP",
            module.dims.np,
            "Number of standard parameters.",
            names_parameters(module),
        ),
        (
            "NB",
            module.dims.nb,
            "Number of base parameters.",
            names_parameters(module),
        ),
    ];
    for (size, value, doc, present) in sizes {
        if present {
            writeln!(h, "/** {doc} */\n#define {upper}_{size} {value}").expect(TEXT);
        }
    }
    for (array, doc, names) in name_arrays(name, module) {
        writeln!(
            h,
            "{}extern const char *const {array}[{}];",
            c_comment(doc, true),
            names.len()
        )
        .expect(TEXT);
    }
    h.push_str(&params_declaration(name, module));
    h.push_str(declarations);
    write!(h, "\n#ifdef __cplusplus\n}}\n#endif\n\n#endif\n").expect(TEXT);
    h
}

/// What q, qd, qdd and tau hold.
fn state_doc(module: &GeneratedPrograms) -> String {
    let (nq, nv) = (module.nq, module.dims.nv);
    match module.floating_base {
        true => format!(
            "q holds the {nq} coordinates of the configuration: the floating base's position and \
             orientation quaternion [x, y, z, qx, qy, qz, qw], then the joint positions; qd, qdd \
             and tau the {nv} velocities, accelerations and generalised forces: the base's \
             linear then angular ones, in the base frame, then the joints'."
        ),
        false => format!(
            "q holds the {nq} joint positions; qd, qdd and tau the {nv} joint velocities, \
             accelerations and generalised forces."
        ),
    }
}

/// Whether the module names its frames: it has a kinematics kernel.
fn names_frames(module: &GeneratedPrograms) -> bool {
    module.kernels.iter().any(|k| k.kernel.is_kinematics())
}

/// Whether the module names its parameters: an identification kernel, or base parameters.
fn names_parameters(module: &GeneratedPrograms) -> bool {
    module.parameter_mode == ParameterMode::Base
        || module.kernels.iter().any(|k| k.kernel.is_identification())
}

/// The name arrays the module declares: (C name, doc, names), none empty.
fn name_arrays<'a>(
    name: &str,
    module: &'a GeneratedPrograms,
) -> Vec<(String, &'static str, &'a [String])> {
    let mut arrays: Vec<(String, &'static str, &'a [String])> = vec![(
        format!("{name}_joint_names"),
        "Joint variable names, in the order of the joint positions in q and the joint velocities in qd.",
        &module.joints,
    )];
    if names_frames(module) {
        arrays.push((
            format!("{name}_frame_names"),
            "The frames of the kinematics functions (link names), in output order.",
            &module.frames,
        ));
    }
    if names_parameters(module) {
        arrays.push((
            format!("{name}_parameter_names"),
            "The standard parameters (per body m, m*cx, m*cy, m*cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz about the body origin; then per joint fv, fc, f0, Ia as present), in the regressor's column order.",
            &module.parameter_names,
        ));
        arrays.push((
            format!("{name}_base_parameter_names"),
            "The base parameters, in the base regressor's column order: each named after the standard parameter it keeps, with R when others are regrouped into it.",
            &module.base_parameter_names,
        ));
    }
    arrays.retain(|(_, _, names)| !names.is_empty());
    arrays
}

/// The name arrays' definitions.
fn name_definitions(name: &str, module: &GeneratedPrograms) -> String {
    let mut c = String::new();
    for (array, _, names) in name_arrays(name, module) {
        let names: Vec<String> = names.iter().map(|n| c_string(n)).collect();
        write!(
            c,
            "\nconst char *const {array}[{}] = {{\n    {}}};\n",
            names.len(),
            names.join(",\n    ")
        )
        .expect(TEXT);
    }
    c
}

/// The C field of each runtime parameter, by symbol index, checked: a C identifier, and no
/// C or C++ keyword.
fn parameter_fields(module: &GeneratedPrograms) -> Result<Vec<String>, CodegenError> {
    let declared = module.runtime_parameters.iter().map(|p| &p.name);
    for name in module.parameter_symbols.iter().chain(declared) {
        if !is_c_identifier(name) {
            return Err(CodegenError::CParameterName(name.clone()));
        }
    }
    Ok(module.parameter_symbols.clone())
}

/// `struct <name>_params`, its default and, for base parameters, the function from the
/// standard ones: declarations.
fn params_declaration(name: &str, module: &GeneratedPrograms) -> String {
    let parameters = &module.runtime_parameters;
    if module.parameter_mode == ParameterMode::Constant {
        return String::new();
    }
    let mut h = String::new();
    let doc = match module.parameter_mode {
        ParameterMode::Base => "The base parameters (NB of them), read at run time: the combinations of the standard parameters the dynamics determine.",
        _ => "The model parameters, read at run time.",
    };
    writeln!(h, "\n/** {doc} */\nstruct {name}_params {{").expect(TEXT);
    for p in parameters {
        writeln!(
            h,
            "    double {}; /**< spec value {} */",
            p.name,
            c_double(p.value)
        )
        .expect(TEXT);
    }
    writeln!(h, "}};\n\n/** The parameters of the robot file. */\nextern const struct {name}_params {name}_default_params;").expect(TEXT);
    if module.parameter_mode == ParameterMode::Base && module.base_parameters.is_some() {
        writeln!(
            h,
            "\n/** Writes to *p the base parameters of the standard parameters standard[{np}] (in the order of {name}_parameter_names). */\nvoid {name}_params_from_standard(const double standard[{np}], struct {name}_params *p);",
            np = module.dims.np
        )
        .expect(TEXT);
    }
    h
}

/// The parameters' default and, for base parameters, the function from the standard ones.
fn params_definitions(name: &str, module: &GeneratedPrograms) -> String {
    if module.parameter_mode == ParameterMode::Constant {
        return String::new();
    }
    let defaults: Vec<String> = module
        .runtime_parameters
        .iter()
        .map(|p: &Parameter| {
            if p.value.is_finite() {
                c_double(p.value)
            } else {
                "0.0".to_owned()
            }
        })
        .collect();
    let mut c = String::new();
    write!(
        c,
        "\nconst struct {name}_params {name}_default_params = {{\n    {}}};\n",
        defaults.join(",\n    ")
    )
    .expect(TEXT);
    if let (ParameterMode::Base, Some(base)) = (module.parameter_mode, &module.base_parameters) {
        writeln!(
            c,
            "\nvoid {name}_params_from_standard(const double standard[{}], struct {name}_params *p) {{",
            module.dims.np
        )
        .expect(TEXT);
        for (b, field) in module
            .runtime_parameters
            .iter()
            .map(|p| &p.name)
            .enumerate()
        {
            write!(c, "    p->{field} = standard[{}]", base.independent[b]).expect(TEXT);
            for (&k, &d) in base.k[b].iter().zip(&base.dependent) {
                if k != 0.0 {
                    let sign = if k < 0.0 { '-' } else { '+' };
                    write!(c, " {sign} {} * standard[{d}]", c_double(k.abs())).expect(TEXT);
                }
            }
            c.push_str(";\n");
        }
        c.push_str("}\n");
    }
    c
}

/// The runtime's functions the kernels call, each only if one does (an unused static
/// function is a warning).
fn helpers(module: &GeneratedPrograms) -> String {
    let instrs = || module.kernels.iter().flat_map(|k| k.program.instrs.iter());
    let non_joint = |a: &Operand| !matches!(a, Operand::Input(rne_symbolic::Symbol::Position(_)));
    let trig = instrs().any(|i| matches!(i, Instr::Sin(_) | Instr::Cos(_)));
    let fused = instrs().any(|i| {
        matches!(
            i,
            Instr::MulAdd(..) | Instr::MulSub(..) | Instr::NegMulAdd(..)
        )
    });
    let mut c = String::new();
    if trig || fused {
        c.push('\n');
        c.push_str(MUL_ADD);
    }
    if trig {
        c.push('\n');
        c.push_str(TRIG);
    }
    if instrs().any(|i| matches!(i, Instr::Sin(a) if non_joint(a))) {
        c.push('\n');
        c.push_str(SIN);
    }
    if instrs().any(|i| matches!(i, Instr::Cos(a) if non_joint(a))) {
        c.push('\n');
        c.push_str(COS);
    }
    if instrs().any(|i| matches!(i, Instr::Sign(_))) {
        c.push('\n');
        c.push_str(SIGN);
    }
    if module
        .kernels
        .iter()
        .any(|k| k.program.instrs.len() > function::SPLIT_ABOVE)
    {
        c.push('\n');
        c.push_str(parts::NOINLINE);
    }
    c
}
