//! What a newcomer meets first: a mistyped built-in name, an MJCF file, an `--out` that cannot
//! be written, a pipe closed by `head` — each a clear line, or silence, never a long wait or a
//! wrong message.

mod common;
use common::rne;

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn scratch(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("rne-cli-trust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn a_mistyped_builtin_name_points_to_rne_models_and_the_closest_name() {
    let e = rne(&["check", "pandaa"]).unwrap_err();
    assert!(e.contains("not a built-in robot"), "{e}");
    assert!(e.contains("rne models"), "{e}");
    assert!(e.contains("did you mean panda"), "{e}");
}

#[test]
fn an_mjcf_file_is_named_as_such_by_extension_and_by_root_element() {
    let model = "<mujoco model=\"arm\"><worldbody/></mujoco>\n";
    for name in ["arm.xml", "arm.urdf"] {
        let e = rne(&["check", &scratch(name, model)]).unwrap_err();
        assert!(
            e.contains("MJCF") && e.contains("not supported yet"),
            "{name}: {e}"
        );
    }
}

#[test]
fn an_out_directory_that_cannot_be_written_is_refused_before_the_work() {
    let start = Instant::now();
    let e = rne(&["stress", "--quick", "--quiet", "--out", "/dev/null/x"]).unwrap_err();
    assert!(e.contains("--out /dev/null/x"), "{e}");
    assert!(
        start.elapsed() < Duration::from_secs(2),
        "{:?}",
        start.elapsed()
    );
}

#[test]
fn a_pipe_closed_by_its_reader_ends_the_command_quietly() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rne"))
        .args(["show", "panda", "--what", "M", "--max-size", "2M"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{:?}: {stderr}", output.status);
    assert!(stderr.is_empty(), "{stderr}");
}
