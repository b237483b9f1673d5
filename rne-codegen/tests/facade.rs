//! The facade's boundary: `rne-codegen` exports what users use — the macro, the runtime and,
//! with `builder`, the build-script API — and nothing of the generator behind it
//! (docs/architecture.md, "The API boundary").

use std::collections::BTreeSet;

/// Everything `rne-codegen` exports, with every feature: the macro, the runtime, and the
/// build-script API with its settings, results and error.
const INTENDED: &[&str] = &[
    // The macro.
    "derive_dynamics",
    // The runtime generated code calls, and what generic code names it by.
    "batch",
    "lanes",
    "sin_cos",
    "sin_cos_array",
    "DoubleDouble",
    "Dynamics",
    "Identification",
    "Input",
    "Kernel",
    "Kinematics",
    "Lanes",
    "OrderedReal",
    "Real",
    "Shape",
    "UnknownKernel",
    "F32x8",
    "F64x4",
    "convert",
    // The build-script API (feature `builder`).
    "generate_from_path",
    "Builder",
    "CodegenError",
    "ForwardDynamicsChoice",
    "ForwardDynamicsMethod",
    "GeneratedModule",
    "GenerationOptions",
    "KernelReport",
    "MimicMode",
    "ParameterMode",
    "ScalarType",
    "Scene",
    "KEEP_GENERATED_ENV",
    "Base",
    "SpecWarning",
];

/// `text` without its `//` comments (doc comments included) and without the body of the
/// hidden module `__private`, which is what generated code reaches the runtime by.
fn without_comments(text: &str) -> String {
    let code = text
        .lines()
        .map(|line| line.split("//").next().unwrap_or_default())
        .collect::<Vec<_>>()
        .join("\n");
    let Some(start) = code.find("pub mod __private") else {
        return code;
    };
    let open = start + code[start..].find('{').unwrap_or(0);
    let mut depth = 0;
    for (i, c) in code[open..].char_indices() {
        depth += match c {
            '{' => 1,
            '}' => -1,
            _ => 0,
        };
        if depth == 0 {
            return format!("{}{}", &code[..start], &code[open + i + 1..]);
        }
    }
    code
}

/// The names `lib.rs` makes public at the crate root: each `pub use`'s last segments (or
/// their `as` renamings) and each `pub mod`, the hidden `__private` left out.
fn exported_names(lib: &str) -> BTreeSet<String> {
    let code = without_comments(lib);
    let mut names = BTreeSet::new();
    for item in code.split(';') {
        let item = item.split_whitespace().collect::<Vec<_>>().join(" ");
        let Some(start) = item.find("pub use ").or_else(|| item.find("pub mod ")) else {
            continue;
        };
        let item = &item[start..];
        if let Some(module) = item.strip_prefix("pub mod ") {
            names.insert(
                module
                    .split([' ', '{'])
                    .next()
                    .unwrap_or_default()
                    .to_owned(),
            );
            continue;
        }
        let path = &item["pub use ".len()..];
        let list = match (path.find('{'), path.rfind('}')) {
            (Some(open), Some(close)) => &path[open + 1..close],
            _ => path.rsplit("::").next().unwrap_or_default(),
        };
        for entry in list.split(',').map(str::trim).filter(|e| !e.is_empty()) {
            let name = entry.rsplit(" as ").next().unwrap_or(entry);
            names.insert(name.rsplit("::").next().unwrap_or(name).to_owned());
        }
    }
    names
}

/// The facade's source lists exactly the intended names: an internal of the generator
/// (`Program`, `kernel_program`, `build_kernel_with`, `KernelSetup`, ...) re-exported here
/// fails this test, and so does a user-facing item dropped.
#[test]
fn the_facade_exports_exactly_the_user_facing_items() {
    let lib = include_str!("../src/lib.rs");
    let exported = exported_names(lib);
    let intended: BTreeSet<String> = INTENDED.iter().map(|s| s.to_string()).collect();
    let extra: Vec<_> = exported.difference(&intended).collect();
    let missing: Vec<_> = intended.difference(&exported).collect();
    assert!(
        extra.is_empty() && missing.is_empty(),
        "exported but not user-facing: {extra:?}; user-facing but not exported: {missing:?}"
    );
}

/// The reader of `lib.rs` finds braced lists, single items, renamings and modules, and skips
/// comments and the hidden module.
#[test]
fn the_export_reader_reads_every_form_of_pub_use() {
    let lib = "/// docs: pub use nothing;\npub use a::{B, c::D,\n    E as F};\n#[cfg(x)]\n\
               pub use g::H;\npub mod i;\n#[doc(hidden)]\npub mod __private {\n    pub use r::*;\n}\n\
               use j::K;\n";
    let names: Vec<String> = exported_names(lib).into_iter().collect();
    assert_eq!(names, ["B", "D", "F", "H", "i"]);
}

/// Every user-facing item of the build-script API is reachable through the facade alone, by
/// the names a build script writes: a module generated with non-default settings, its report
/// and its warnings.
#[test]
fn a_build_script_needs_nothing_but_the_facade() {
    use rne_codegen::{
        generate_from_path, Base, Builder, CodegenError, ForwardDynamicsChoice,
        ForwardDynamicsMethod, GeneratedModule, GenerationOptions, Kernel, KernelReport, MimicMode,
        ParameterMode, ScalarType, Scene, SpecWarning, KEEP_GENERATED_ENV,
    };
    let robot = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/robots/irb140-3dof.toml");
    let builder = Builder::new(robot)
        .outputs(&[Kernel::InverseDynamics, Kernel::ForwardDynamics])
        .base(Base::Fixed)
        .mimic(MimicMode::Constrained)
        .forward_dynamics(ForwardDynamicsMethod::Auto)
        .parameters(ParameterMode::Constant)
        .scalar(ScalarType::F64);
    let (module, warnings): (GeneratedModule, Vec<SpecWarning>) = builder
        .generate_with_warnings()
        .expect("the robot generates");
    let reports: &[KernelReport] = &module.kernels;
    assert_eq!(reports.len(), 2);
    let choice: Option<&ForwardDynamicsChoice> = module.forward_dynamics_choice.as_ref();
    assert!(
        choice.is_some(),
        "both algorithms apply to a fixed 3-joint arm"
    );
    assert!(warnings.is_empty(), "{warnings:?}");
    let scene: &Scene = builder.scene();
    let options: &GenerationOptions = builder.options();
    let again = generate_from_path(robot.as_ref(), scene, options).expect("the same module");
    assert_eq!(again.source, module.source);
    let missing: Result<_, CodegenError> =
        generate_from_path("no/such.toml".as_ref(), scene, options);
    assert!(missing.unwrap_err().to_string().contains("no/such.toml"));
    assert_eq!(KEEP_GENERATED_ENV, "RNE_KEEP_GENERATED");
}

/// The build-script API's names, what the facade exports only with the feature `builder`:
/// [`INTENDED`] from its first build-script item on.
fn builder_only() -> &'static [&'static str] {
    let first = INTENDED
        .iter()
        .position(|name| *name == "generate_from_path")
        .expect("the build-script API is listed");
    &INTENDED[first..]
}

/// The Rust files under `dir`, recursively.
fn rust_files(dir: &std::path::Path, found: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for path in entries.flatten().map(|e| e.path()) {
        if path.is_dir() {
            rust_files(&path, found);
        } else if path.extension().is_some_and(|e| e == "rs") {
            found.push(path);
        }
    }
}

/// The build-script names `code` takes from the facade by a path `rne_codegen::…` (a `use`
/// with or without braces, or a qualified name), up to the end of each statement.
fn builder_names_used(code: &str) -> BTreeSet<String> {
    let code = without_comments(code);
    let mut used = BTreeSet::new();
    for (start, _) in code.match_indices("rne_codegen::") {
        let rest = &code[start + "rne_codegen::".len()..];
        let statement = &rest[..rest.find([';', '(', '=']).unwrap_or(rest.len())];
        for word in statement.split(|c: char| !(c.is_alphanumeric() || c == '_')) {
            if builder_only().contains(&word) {
                used.insert(word.to_owned());
            }
        }
    }
    used
}

/// A sibling crate whose manifest does not turn on the facade's `builder` takes none of the
/// build-script names from the facade in its sources: it takes them from rne-codegen-core.
/// Inside the workspace another crate's `builder` would hide the mistake (Cargo unifies
/// features), but a build of that crate alone — the README's `cargo run -p rne-cli` — fails.
#[test]
fn crates_without_the_builder_feature_take_the_generator_from_core() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let manifest = std::fs::read_to_string(format!("{root}/Cargo.toml")).expect("root manifest");
    let members: Vec<&str> = manifest
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with('"') && l.ends_with("\","))
        .map(|l| l.trim_matches(|c| c == '"' || c == ','))
        .collect();
    assert!(
        members.contains(&"rne-models/cli"),
        "members read: {members:?}"
    );
    let mut wrong = Vec::new();
    for member in members {
        let crate_manifest =
            std::fs::read_to_string(format!("{root}/{member}/Cargo.toml")).unwrap_or_default();
        if crate_manifest.contains("features = [\"builder\"]") || member == "rne-codegen" {
            continue;
        }
        let mut files = Vec::new();
        rust_files(format!("{root}/{member}/src").as_ref(), &mut files);
        for file in files {
            let used = builder_names_used(&std::fs::read_to_string(&file).unwrap_or_default());
            if !used.is_empty() {
                wrong.push(format!("{}: {used:?}", file.display()));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "take these from rne_codegen_core: {wrong:#?}"
    );
}

#[test]
fn the_builder_name_reader_sees_braced_and_qualified_paths() {
    let code = "use rne_codegen::{Kernel, Scene};\nuse rne_codegen_core::Builder;\n\
                let s = rne_codegen::GenerationOptions::default();\n// rne_codegen::Base\n";
    let used: Vec<String> = builder_names_used(code).into_iter().collect();
    assert_eq!(used, ["GenerationOptions", "Scene"]);
}
