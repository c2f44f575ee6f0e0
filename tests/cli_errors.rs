//! Bad input to `ancf-modal modal [MODEL]`, end to end through the binary.
//!
//! The requirement: every kind of bad model gives exit code 1, an empty
//! stdout, no output file, and exactly one line on stderr,
//! `Error: <file>: <json path>: <problem>` (syntax errors:
//! `Error: <file>:<line>:<col>: malformed JSON: …`) — never a panic, a
//! backtrace or a multi-line dump. Each case starts from the valid model of
//! [`minimal`] and changes one thing. Usage errors too are one line, exit 1; a few
//! positive runs pin the table, JSON and CSV outputs.

use assert_cmd::cargo::cargo_bin_cmd;
use serde_json::{json, Value};
use std::path::Path;
use tempfile::TempDir;

// ---------------------------------------------------------------- harness

/// A small valid model: a free beam with a rigid body welded at s = 20 mm,
/// a point mass pinned at node 0, one load and one sensor.
fn minimal() -> Value {
    json!({
        "name": "minimal",
        "beams": [{
            "id": "blade", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.025,
            "elements": 4,
            "section": {"height": 1.1e-3, "width": 5.2e-3},
            "material": {"young": 127e9, "density": 8940.0}
        }],
        "rigid_bodies": [{"id": "slot", "mass": 0.5e-3, "inertia": 3e-9, "position": [0.02, 0.0]}],
        "point_masses": [{"id": "pad", "mass": 0.3e-3, "position": [0.0, 0.0]}],
        "joints": [
            {"type": "weld", "a": {"body": "slot"}, "b": {"beam": "blade", "s": 0.02}},
            {"type": "pin", "a": {"body": "pad"}, "b": {"beam": "blade", "s": 0.0}}
        ],
        "loads": [{"at": {"beam": "blade", "s": 0.0}, "frame": "beam", "force": [0.0, 1.0]}],
        "sensors": [{"id": "tip", "at": {"beam": "blade", "s": 0.025},
                     "quantity": "velocity", "direction": [0.0, 1.0]}]
    })
}

/// [`minimal`] with one change, as model-file text.
fn edited(change: impl FnOnce(&mut Value)) -> String {
    let mut model = minimal();
    change(&mut model);
    serde_json::to_string_pretty(&model).expect("a JSON value serializes")
}

/// A spring from the rigid body's centre to a ground point 10 mm above it.
fn spring(extra: Value) -> Value {
    let mut s = json!({"a": {"body": "slot"}, "b": {"ground": [0.02, 0.01]}, "stiffness": 100.0});
    let (Value::Object(s_map), Value::Object(extra)) = (&mut s, extra) else {
        panic!("spring() takes an object");
    };
    s_map.extend(extra);
    s
}

/// One failing run: the single stderr line and the model file's path as the
/// message prints it.
struct Failure {
    line: String,
    file: String,
}

impl Failure {
    /// Asserts the `Error: <file>: <path>: …` form and that every fragment
    /// of the problem appears.
    fn names(&self, path: &str, fragments: &[&str]) {
        let prefix = format!("Error: {}: {path}: ", self.file);
        assert!(
            self.line.starts_with(&prefix),
            "the message names the file and the JSON path `{path}`:\n  expected prefix {prefix:?}\n  got {:?}",
            self.line
        );
        self.says(fragments);
    }

    /// Asserts that every fragment appears in the message.
    fn says(&self, fragments: &[&str]) {
        for f in fragments {
            assert!(
                self.line.contains(f),
                "the message states the problem ({f:?}):\n  got {:?}",
                self.line
            );
        }
    }

    /// Asserts `Error: <file>:<line>:<col>: <rest>` and returns (line, col, rest).
    fn position(&self) -> (usize, usize, &str) {
        let prefix = format!("Error: {}:", self.file);
        let rest = self.line.strip_prefix(&prefix).unwrap_or_else(|| {
            panic!(
                "the message starts with `Error: <file>:`, got {:?}",
                self.line
            )
        });
        let mut parts = rest.splitn(3, ':');
        let mut number = |what: &str| -> usize {
            parts
                .next()
                .and_then(|p| p.parse().ok())
                .unwrap_or_else(|| {
                    panic!(
                        "the message gives the {what} number after the file, got {:?}",
                        self.line
                    )
                })
        };
        let (line, col) = (number("line"), number("column"));
        let rest = parts.next().unwrap_or_default();
        let rest = rest.strip_prefix(' ').unwrap_or_else(|| {
            panic!(
                "`<file>:<line>:<col>: ` is followed by a space, got {:?}",
                self.line
            )
        });
        (line, col, rest)
    }
}

/// Runs `ancf-modal modal <file> --csv <dir>/out.csv` and checks every rule
/// common to bad input; the model file must already be in `dir`.
fn run_failing(dir: &TempDir, model: &Path) -> Failure {
    let csv = dir.path().join("out.csv");
    let before = entries(dir.path());
    let out = cargo_bin_cmd!("ancf-modal")
        .arg("modal")
        .arg(model)
        .arg("--csv")
        .arg(&csv)
        // A panic would then print a backtrace, which the checks reject.
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("the binary runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(1),
        "exit code of bad input is 1; stderr: {stderr}"
    );
    assert!(
        stdout.is_empty(),
        "stdout is empty on an error, got {stdout:?}"
    );
    assert_eq!(
        stderr.lines().count(),
        1,
        "stderr is exactly one line, got {stderr:?}"
    );
    assert!(
        stderr.ends_with('\n'),
        "the stderr line is terminated, got {stderr:?}"
    );
    for bad in ["panicked", "backtrace", "RUST_BACKTRACE", "Caused by"] {
        assert!(
            !stderr.contains(bad),
            "no panic, backtrace or error chain on stderr ({bad:?}), got {stderr:?}"
        );
    }
    assert!(
        !stderr.contains(" { "),
        "no Debug dump of an error struct on stderr, got {stderr:?}"
    );
    assert!(
        stderr.starts_with("Error: "),
        "the line starts with `Error: `, got {stderr:?}"
    );
    assert!(
        !csv.exists(),
        "no output file is created on an error ({})",
        csv.display()
    );
    assert_eq!(
        entries(dir.path()),
        before,
        "no file at all (not even a temporary one) is left in the output directory"
    );
    Failure {
        line: stderr.trim_end_matches('\n').to_string(),
        file: model.display().to_string(),
    }
}

/// Writes `text` as `model.json` into a fresh temp dir and runs [`run_failing`].
fn fails(text: &str) -> Failure {
    fails_bytes(text.as_bytes())
}

fn fails_bytes(bytes: &[u8]) -> Failure {
    let dir = TempDir::new().expect("a temp dir");
    let model = dir.path().join("model.json");
    std::fs::write(&model, bytes).expect("the model file is written");
    run_failing(&dir, &model)
}

/// Sorted names in a directory.
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("the temp dir is readable")
        .map(|e| {
            e.expect("a directory entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}

/// Runs the binary with `args` in `dir`; returns (exit code, stdout, stderr).
fn run(args: &[&str], dir: &Path) -> (Option<i32>, String, String) {
    let out = cargo_bin_cmd!("ancf-modal")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs `modal <model> [args]` on a valid model; asserts success, returns stdout.
fn succeeds(text: &str, args: &[&str]) -> String {
    let dir = TempDir::new().expect("a temp dir");
    let model = dir.path().join("model.json");
    std::fs::write(&model, text).expect("the model file is written");
    let mut all = vec!["modal", model.to_str().expect("a UTF-8 temp path")];
    all.extend_from_slice(args);
    let (code, stdout, stderr) = run(&all, dir.path());
    assert_eq!(
        code,
        Some(0),
        "a valid model analyses with exit code 0; stderr: {stderr}"
    );
    stdout
}

// ---------------------------------------------------------- the harness's base

#[test]
fn the_minimal_model_is_valid() {
    let stdout = succeeds(&edited(|_| {}), &[]);
    assert!(
        stdout.contains("bending"),
        "the base model of the error cases analyses and has bending modes:\n{stdout}"
    );
}

// ------------------------------------------------------------- malformed JSON

#[test]
fn truncated_json() {
    let text = edited(|_| {});
    let cut = &text[..text.len() / 2];
    let f = fails(cut);
    let (line, _, rest) = f.position();
    assert_eq!(
        line,
        1 + cut.matches('\n').count(),
        "the position is the end of the truncated file: {}",
        f.line
    );
    assert!(
        rest.starts_with("malformed JSON: EOF while parsing"),
        "the problem is an unexpected end of file: {}",
        f.line
    );
}

#[test]
fn empty_file() {
    let f = fails("");
    let (line, _, rest) = f.position();
    assert_eq!(line, 1, "an empty file fails on line 1: {}", f.line);
    assert_eq!(
        rest, "malformed JSON: EOF while parsing a value",
        "the problem of an empty file"
    );
}

#[test]
fn trailing_comma() {
    let text = "{\n  \"name\": \"x\",\n  \"point_masses\": [{\"id\": \"m\", \"mass\": 1.0, \"position\": [0.0, 0.0],}]\n}\n";
    let f = fails(text);
    let (line, col, rest) = f.position();
    assert_eq!(
        (line, col),
        (3, 68),
        "the position is the `}}` after the trailing comma: {}",
        f.line
    );
    assert_eq!(rest, "malformed JSON: trailing comma", "the problem");
}

#[test]
fn trailing_characters_after_the_model() {
    let text = format!("{}\n}}\n", edited(|_| {}));
    let f = fails(&text);
    let (line, col, rest) = f.position();
    assert_eq!(
        (line, col),
        (text.lines().count(), 1),
        "the position is the stray `}}`: {}",
        f.line
    );
    assert_eq!(rest, "malformed JSON: trailing characters", "the problem");
}

#[test]
fn not_utf8() {
    let mut bytes = edited(|_| {}).into_bytes();
    bytes.extend_from_slice(b"\xff\xfe");
    let f = fails_bytes(&bytes);
    assert!(
        f.line
            .starts_with(&format!("Error: {}: cannot read the file: ", f.file)),
        "the message names the file and says it cannot be read: {}",
        f.line
    );
    f.says(&["UTF-8"]);
}

// --------------------------------------------------------------- schema errors

#[test]
fn unknown_key_at_top_level() {
    let f = fails(&edited(|m| m["hieght"] = json!(1.0)));
    f.names(
        "hieght",
        &["unknown field `hieght`", "expected one of `name`"],
    );
}

#[test]
fn unknown_key_nested() {
    let f = fails(&edited(|m| {
        m["beams"][0]["section"]["hieght"] = json!(1e-3)
    }));
    f.names(
        "beams[0].section.hieght",
        &["unknown field `hieght`", "expected `height` or `width`"],
    );
}

#[test]
fn unknown_key_in_a_point() {
    let f = fails(&edited(|m| m["joints"][1]["b"]["arc"] = json!(0.0)));
    f.names("joints[1].b.arc", &["unknown field `arc`"]);
}

#[test]
fn unknown_key_in_a_load_time_function() {
    let f = fails(&edited(|m| {
        m["loads"][0]["time"] = json!({"half_sine": {"duraton": 1e-4}})
    }));
    f.names(
        "loads[0].time.half_sine.duraton",
        &["unknown field `duraton`", "`duration`"],
    );
}

#[test]
fn unknown_joint_type() {
    let f = fails(&edited(|m| m["joints"][0]["type"] = json!("hinge")));
    f.names(
        "joints[0].type",
        &["unknown variant `hinge`", "`pin`, `weld`, `slider`"],
    );
}

#[test]
fn missing_required_field() {
    let f = fails(&edited(|m| {
        m["beams"][0]
            .as_object_mut()
            .expect("a beam object")
            .remove("length");
    }));
    f.names("beams[0]", &["missing field `length`"]);
}

#[test]
fn missing_model_name() {
    let f = fails(&edited(|m| {
        m.as_object_mut().expect("a model object").remove("name");
    }));
    f.names("$", &["missing field `name`"]);
}

#[test]
fn wrong_type_string_for_a_number() {
    let f = fails(&edited(|m| m["beams"][0]["length"] = json!("0.025")));
    f.names(
        "beams[0].length",
        &["invalid type: string \"0.025\", expected f64"],
    );
}

#[test]
fn wrong_type_fraction_for_a_count() {
    let f = fails(&edited(|m| m["beams"][0]["elements"] = json!(2.5)));
    f.names("beams[0].elements", &["invalid type", "expected usize"]);
}

#[test]
fn negative_element_count() {
    let f = fails(&edited(|m| m["beams"][0]["elements"] = json!(-1)));
    f.names("beams[0].elements", &["invalid value: integer `-1`"]);
}

// ------------------------------------------------------ non-positive values

#[test]
fn beam_length_zero() {
    let f = fails(&edited(|m| m["beams"][0]["length"] = json!(0.0)));
    f.names("beams[0].length", &["must be positive, got 0.0"]);
}

#[test]
fn section_height_negative() {
    let f = fails(&edited(|m| {
        m["beams"][0]["section"]["height"] = json!(-1e-3)
    }));
    f.names("beams[0].section.height", &["must be positive, got -0.001"]);
}

#[test]
fn density_zero() {
    let f = fails(&edited(|m| m["beams"][0]["material"]["density"] = json!(0)));
    f.names("beams[0].material.density", &["must be positive, got 0.0"]);
}

#[test]
fn young_negative() {
    let f = fails(&edited(|m| {
        m["beams"][0]["material"]["young"] = json!(-127e9)
    }));
    f.names(
        "beams[0].material.young",
        &["must be positive, got -127000000000.0"],
    );
}

#[test]
fn rigid_body_mass_zero() {
    let f = fails(&edited(|m| m["rigid_bodies"][0]["mass"] = json!(0.0)));
    f.names("rigid_bodies[0].mass", &["must be positive, got 0.0"]);
}

#[test]
fn point_mass_negative_mass() {
    let f = fails(&edited(|m| m["point_masses"][0]["mass"] = json!(-0.3e-3)));
    f.names("point_masses[0].mass", &["must be positive, got -0.0003"]);
}

#[test]
fn spring_stiffness_zero() {
    let f = fails(&edited(|m| {
        m["springs"] = json!([spring(json!({"stiffness": 0.0, "free_length": 0.01}))])
    }));
    f.names("springs[0].stiffness", &["must be positive, got 0.0"]);
}

#[test]
fn elements_zero() {
    let f = fails(&edited(|m| m["beams"][0]["elements"] = json!(0)));
    f.names("beams[0].elements", &["must be at least 1, got 0"]);
}

#[test]
fn elements_beyond_available_memory() {
    // 10⁸ elements would abort with a failed allocation, not an error line.
    let f = fails(&edited(|m| m["beams"][0]["elements"] = json!(100_000_000)));
    f.names(
        "beams[0].elements",
        &["100000000 elements", "available memory holds"],
    );
}

#[test]
fn inertia_negative() {
    let f = fails(&edited(|m| m["rigid_bodies"][0]["inertia"] = json!(-3e-9)));
    f.names(
        "rigid_bodies[0].inertia",
        &["must not be negative, got -3e-9"],
    );
}

// ---------------------------------------------------------------- non-finite

#[test]
fn number_beyond_f64_range() {
    // JSON has no NaN or infinity; `1e999` is valid JSON that serde_json
    // refuses ("number out of range"). The message keeps the position and
    // adds the JSON path.
    let text = edited(|m| m["beams"][0]["length"] = json!("@")).replace("\"@\"", "1e999");
    let f = fails(&text);
    let (line, _, rest) = f.position();
    let expected_line = 1 + text
        .lines()
        .position(|l| l.contains("1e999"))
        .expect("the text has the number");
    assert_eq!(
        line, expected_line,
        "the position is the line of `1e999`: {}",
        f.line
    );
    assert!(
        rest.starts_with("beams[0].length: number out of range: "),
        "the message names the JSON path and the problem: {}",
        f.line
    );
    f.says(&["finite"]);
}

// ----------------------------------------------------------------------- ids

#[test]
fn duplicate_body_id() {
    let f = fails(&edited(|m| m["point_masses"][0]["id"] = json!("blade")));
    f.names("point_masses[0].id", &["id `blade` is used twice"]);
}

#[test]
fn duplicate_sensor_id() {
    let f = fails(&edited(|m| {
        let s = m["sensors"][0].clone();
        m["sensors"].as_array_mut().expect("sensors").push(s);
    }));
    f.names("sensors[1].id", &["id `tip` is used twice"]);
}

#[test]
fn duplicate_joint_id() {
    let f = fails(&edited(|m| {
        m["joints"][0]["id"] = json!("j");
        m["joints"][1]["id"] = json!("j");
    }));
    f.names("joints[1].id", &["id `j` is used twice"]);
}

#[test]
fn empty_id() {
    let f = fails(&edited(|m| m["rigid_bodies"][0]["id"] = json!(" ")));
    f.names("rigid_bodies[0].id", &["must not be empty"]);
}

#[test]
fn unknown_beam_in_a_joint() {
    let f = fails(&edited(|m| m["joints"][0]["b"]["beam"] = json!("blad")));
    f.names("joints[0].b.beam", &["no beam with id `blad`"]);
}

#[test]
fn unknown_body_in_a_joint() {
    let f = fails(&edited(|m| m["joints"][0]["a"]["body"] = json!("slt")));
    f.names(
        "joints[0].a.body",
        &["no rigid body or point mass with id `slt`"],
    );
}

#[test]
fn unknown_body_in_a_spring() {
    let f = fails(&edited(|m| {
        let mut s = spring(json!({"free_length": 0.01}));
        s["a"]["body"] = json!("slt");
        m["springs"] = json!([s]);
    }));
    f.names(
        "springs[0].a.body",
        &["no rigid body or point mass with id `slt`"],
    );
}

#[test]
fn unknown_beam_in_a_spring() {
    let f = fails(&edited(|m| {
        let mut s = spring(json!({"free_length": 0.01}));
        s["a"] = json!({"beam": "blad", "s": 0.0});
        m["springs"] = json!([s]);
    }));
    f.names("springs[0].a.beam", &["no beam with id `blad`"]);
}

#[test]
fn unknown_beam_in_a_load() {
    let f = fails(&edited(|m| m["loads"][0]["at"]["beam"] = json!("blad")));
    f.names("loads[0].at.beam", &["no beam with id `blad`"]);
}

#[test]
fn unknown_body_in_a_load() {
    let f = fails(&edited(|m| {
        m["loads"][0]["at"] = json!({"body": "slt"});
        m["loads"][0]["frame"] = json!("global");
    }));
    f.names(
        "loads[0].at.body",
        &["no rigid body or point mass with id `slt`"],
    );
}

#[test]
fn unknown_beam_in_a_sensor() {
    let f = fails(&edited(|m| m["sensors"][0]["at"]["beam"] = json!("blad")));
    f.names("sensors[0].at.beam", &["no beam with id `blad`"]);
}

#[test]
fn unknown_body_in_a_sensor() {
    let f = fails(&edited(|m| {
        m["sensors"][0]["at"] = json!({"body": "slt"});
        m["sensors"][0]["frame"] = json!("global");
    }));
    f.names(
        "sensors[0].at.body",
        &["no rigid body or point mass with id `slt`"],
    );
}

// -------------------------------------------------------------------- points

#[test]
fn s_beyond_the_beam_end() {
    let f = fails(&edited(|m| m["joints"][0]["b"]["s"] = json!(0.03)));
    f.names("joints[0].b.s", &["0.03 is outside [0.0, 0.025]"]);
}

#[test]
fn s_negative() {
    let f = fails(&edited(|m| m["sensors"][0]["at"]["s"] = json!(-0.001)));
    f.names("sensors[0].at.s", &["-0.001 is outside [0.0, 0.025]"]);
}

#[test]
fn s_missing_for_a_beam_point() {
    let f = fails(&edited(|m| {
        m["joints"][0]["b"]
            .as_object_mut()
            .expect("a point object")
            .remove("s");
    }));
    f.names("joints[0].b", &["`s` is required here"]);
}

#[test]
fn point_with_both_beam_and_ground() {
    let f = fails(&edited(|m| {
        m["joints"][0]["b"]["ground"] = json!([0.02, 0.0])
    }));
    f.names(
        "joints[0].b",
        &[
            "give exactly one of `beam`, `body` or `ground`",
            "`beam` and `ground`",
        ],
    );
}

#[test]
fn point_with_none_of_beam_body_ground() {
    let f = fails(&edited(|m| m["loads"][0]["at"] = json!({"s": 0.0})));
    f.names(
        "loads[0].at",
        &["give exactly one of `beam`, `body` or `ground`", "none"],
    );
}

// -------------------------------------------------------------------- joints

#[test]
fn joint_points_apart() {
    let f = fails(&edited(|m| m["joints"][1]["b"]["s"] = json!(0.001)));
    f.names(
        "joints[1]",
        &[
            "the points do not coincide",
            "gap of 1.000e-3 m",
            "[0.0, 0.0]",
            "[0.001, 0.0]",
        ],
    );
}

#[test]
fn joint_with_explicit_local_point_apart() {
    let f = fails(&edited(|m| {
        m["joints"][0]["a"]["local"] = json!([0.0, 0.002])
    }));
    f.names("joints[0]", &["do not coincide", "gap of 2.000e-3 m"]);
}

#[test]
fn weld_to_a_point_mass() {
    let f = fails(&edited(|m| m["joints"][1]["type"] = json!("weld")));
    f.names(
        "joints[1].a",
        &["`pad` is a point mass and has no orientation", "a weld"],
    );
}

#[test]
fn slider_without_axis() {
    let f = fails(&edited(|m| m["joints"][0]["type"] = json!("slider")));
    f.names("joints[0]", &["`axis` is required here"]);
}

#[test]
fn slider_with_zero_axis() {
    let f = fails(&edited(|m| {
        m["joints"][0]["type"] = json!("slider");
        m["joints"][0]["axis"] = json!([0.0, 0.0]);
    }));
    f.names("joints[0].axis", &["non-zero length"]);
}

#[test]
fn torsion_stiffness_on_a_weld() {
    let f = fails(&edited(|m| {
        m["joints"][0]["torsion_stiffness"] = json!(1.0)
    }));
    f.names(
        "joints[0].torsion_stiffness",
        &["not allowed here", "only pins carry torsion springs"],
    );
}

// ------------------------------------------------------------------- springs

#[test]
fn spring_with_free_length_and_preload() {
    let f = fails(&edited(|m| {
        m["springs"] = json!([spring(json!({"free_length": 0.01, "preload": 1.0}))])
    }));
    f.names(
        "springs[0].preload",
        &["give either `free_length` or `preload`"],
    );
}

#[test]
fn spring_with_neither_free_length_nor_preload() {
    let f = fails(&edited(|m| m["springs"] = json!([spring(json!({}))])));
    f.names("springs[0]", &["`free_length` or `preload` is required"]);
}

#[test]
fn spring_preload_leaves_no_free_length() {
    // Initial length 10 mm, k = 100 N/m: a tension of 2 N means l0 = −10 mm.
    let f = fails(&edited(|m| {
        m["springs"] = json!([spring(json!({"preload": 2.0}))])
    }));
    f.names(
        "springs[0].preload",
        &[
            "free length -1.000e-2 m is not positive",
            "preload 2.0 N",
            "stiffness 100.0 N/m",
        ],
    );
}

// --------------------------------------------------------------------- loads

#[test]
fn load_in_beam_frame_on_a_rigid_body() {
    let f = fails(&edited(|m| m["loads"][0]["at"] = json!({"body": "slot"})));
    f.names(
        "loads[0].frame",
        &["`beam` is not allowed here", "needs a beam point"],
    );
}

// --------------------------------------------------------------- whole model

#[test]
fn model_without_bodies() {
    let f = fails(r#"{"name": "empty"}"#);
    f.names("$", &["the model has no bodies"]);
}

#[test]
fn model_not_an_object() {
    let f = fails("42");
    f.names("$", &["invalid type: integer `42`, expected struct Model"]);
}

#[test]
fn nonexistent_model_path() {
    let dir = TempDir::new().expect("a temp dir");
    let model = dir.path().join("no_such_model.json");
    let f = run_failing(&dir, &model);
    assert!(
        f.line
            .starts_with(&format!("Error: {}: cannot read the file: ", f.file)),
        "the message names the missing file and says it cannot be read: {}",
        f.line
    );
    f.says(&["No such file or directory"]);
}

#[test]
fn model_path_is_a_directory() {
    let dir = TempDir::new().expect("a temp dir");
    let model = dir.path().join("models");
    std::fs::create_dir(&model).expect("a sub-directory");
    let f = run_failing(&dir, &model);
    assert!(
        f.line
            .starts_with(&format!("Error: {}: cannot read the file: ", f.file)),
        "a directory as model names the path and says it cannot be read: {}",
        f.line
    );
}

// ------------------------------------------------- singular mass (analysis)

#[test]
fn massless_rotation_free_to_turn_is_singular() {
    // Valid input (inertia 0 is allowed), but pinned without a torsion
    // spring the body's rotation carries no mass: the analysis must refuse
    // it with one line that names the body and the direction.
    let f = fails(&edited(|m| {
        m["rigid_bodies"][0]["inertia"] = json!(0.0);
        m["joints"][0]["type"] = json!("pin");
    }));
    f.says(&["rigid_bodies[0].inertia: the mass matrix is singular in the direction of rigid body `slot` rotation"]);
    assert!(
        f.line
            .starts_with(&format!("Error: {}: rigid_bodies[0].inertia: ", f.file)),
        "names the file and the JSON path: {}",
        f.line
    );
}

#[test]
fn massless_rotation_welded_to_a_beam_analyses() {
    // The same body welded: its rotation follows the beam's slope, so the
    // reduced mass matrix is regular.
    let stdout = succeeds(
        &edited(|m| m["rigid_bodies"][0]["inertia"] = json!(0.0)),
        &["--json"],
    );
    let doc: Value = serde_json::from_str(&stdout).expect("--json prints valid JSON");
    assert_eq!(
        doc["rigid_modes"], 3,
        "a free planar assembly has 3 rigid modes"
    );
}

// -------------------------------------------------------------- usage errors

#[test]
fn usage_errors_are_one_line_and_exit_with_1() {
    let dir = TempDir::new().expect("a temp dir");
    for (args, named) in [
        (&["modal", "--bogus", "--csv", "out.csv"][..], "--bogus"),
        (&["no-such-command"][..], "no-such-command"),
        (&["reduce", "--modes", "4"][..], "--interface"),
        (
            &["reduce", "--interface", "blade:0", "--method", "guyan"][..],
            "guyan",
        ),
        (&["modal", "--load-scale", "2"][..], "--prestress"),
    ] {
        let (code, stdout, stderr) = run(args, dir.path());
        assert_eq!(code, Some(1), "usage error {args:?} exits with 1: {stderr}");
        assert!(stdout.is_empty(), "usage error {args:?}: stdout is empty");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: one line: {stderr}");
        assert!(
            stderr.starts_with("Error: ") && stderr.contains(named),
            "usage error {args:?}: names {named}: {stderr:?}"
        );
        assert!(
            !dir.path().join("out.csv").exists(),
            "usage error {args:?}: no output file"
        );
    }
}

// ------------------------------------------------------------ positive runs

#[test]
fn builtin_model_prints_a_table() {
    let dir = TempDir::new().expect("a temp dir");
    let (code, stdout, stderr) = run(&["modal"], dir.path());
    assert_eq!(
        code,
        Some(0),
        "the built-in model analyses; stderr: {stderr}"
    );
    assert!(
        !stderr.contains("Error"),
        "no error on stderr, got {stderr:?}"
    );
    assert!(
        stdout.contains("rcbo_free_free"),
        "the table names the model"
    );
    assert!(
        stdout.contains("rigid"),
        "the table lists rigid modes:\n{stdout}"
    );
    assert!(
        stdout.contains("bending"),
        "the table lists bending modes:\n{stdout}"
    );
}

#[test]
fn builtin_model_json() {
    let dir = TempDir::new().expect("a temp dir");
    let (code, stdout, stderr) = run(&["modal", "--json"], dir.path());
    assert_eq!(code, Some(0), "--json succeeds; stderr: {stderr}");
    let doc: Value = serde_json::from_str(&stdout).expect("--json prints valid JSON");
    assert_eq!(doc["model"], "rcbo_free_free", "key `model`");
    assert!(
        doc["dofs"].as_u64().is_some_and(|n| n > 0),
        "key `dofs` is a positive count"
    );
    assert_eq!(
        doc["rigid_modes"], 3,
        "key `rigid_modes`: the free-free assembly has 3 rigid modes"
    );
    let modes = doc["modes"].as_array().expect("key `modes` is an array");
    assert_eq!(modes.len(), 12, "`--modes` defaults to 12 reported modes");
    let mut previous = 0.0;
    for (i, m) in modes.iter().enumerate() {
        assert_eq!(
            m["index"],
            i + 1,
            "modes[{i}].index is the 1-based mode number"
        );
        let f = m["frequency_hz"]
            .as_f64()
            .unwrap_or_else(|| panic!("modes[{i}].frequency_hz is a number"));
        assert!(f >= previous, "modes[{i}].frequency_hz ascends");
        previous = f;
        let kind = m["kind"]
            .as_str()
            .unwrap_or_else(|| panic!("modes[{i}].kind is a string"));
        assert_eq!(
            kind == "rigid",
            i < 3,
            "modes[{i}].kind: exactly the first 3 are rigid, got {kind}"
        );
        assert!(
            ["rigid", "bending", "axial"].contains(&kind),
            "modes[{i}].kind is rigid, bending or axial, got {kind}"
        );
    }
    assert_eq!(modes[3]["kind"], "bending", "the first elastic mode bends");
}

#[test]
fn csv_has_the_header_and_one_row_per_mode() {
    let dir = TempDir::new().expect("a temp dir");
    let (code, stdout, stderr) = run(
        &["modal", "--modes", "7", "--json", "--csv", "modes.csv"],
        dir.path(),
    );
    assert_eq!(code, Some(0), "--csv succeeds; stderr: {stderr}");
    let doc: Value = serde_json::from_str(&stdout).expect("--json prints valid JSON");
    let modes = doc["modes"].as_array().expect("key `modes`");
    assert_eq!(modes.len(), 7, "--modes 7 reports 7 modes");
    let csv = std::fs::read_to_string(dir.path().join("modes.csv")).expect("the CSV is written");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("mode,frequency_hz,eigenvalue_rad2_s2,kind,bending_fraction,axial_fraction,spring_fraction,error_bound"),
        "the CSV header"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), modes.len(), "one CSV row per reported mode");
    for (i, (row, mode)) in rows.iter().zip(modes).enumerate() {
        assert_eq!(row.len(), 8, "row {i} has 8 columns");
        assert_eq!(row[0], (i + 1).to_string(), "row {i}: `mode` counts from 1");
        let f: f64 = row[1].parse().expect("frequency_hz is a number");
        let expected = mode["frequency_hz"].as_f64().expect("JSON frequency");
        assert!(
            (f - expected).abs() <= 1e-9 * expected.abs(),
            "row {i}: the CSV frequency {f} matches the JSON {expected}"
        );
        assert_eq!(
            Some(row[3]),
            mode["kind"].as_str(),
            "row {i}: kind matches the JSON"
        );
    }
    assert_eq!(
        entries(dir.path()),
        ["modes.csv"],
        "only the CSV is written (no temporary file left)"
    );
}

#[test]
fn modal_solver_flag_gives_the_same_modes_and_their_error_bounds() {
    // The built-in assembly by the dense path and by shift-invert: the same
    // frequencies (both Rayleigh-refined), each elastic mode with a bound
    // that covers the difference, rigid modes without one.
    let dir = TempDir::new().expect("a temp dir");
    let modes = |solver: &str| -> serde_json::Value {
        let (code, stdout, stderr) = run(
            &["modal", "--json", "--modes", "8", "--solver", solver],
            dir.path(),
        );
        assert_eq!(
            code,
            Some(0),
            "modal --solver {solver} succeeds; stderr: {stderr}"
        );
        serde_json::from_str(&stdout).expect("one JSON document")
    };
    let (dense, sparse) = (modes("dense"), modes("sparse"));
    assert_eq!(dense["solver"], "dense", "the dense path ran");
    assert_eq!(
        sparse["solver"], "sparse shift-invert Lanczos",
        "the sparse path ran"
    );
    assert_eq!(dense["rigid_modes"], 3, "free assembly: 3 zero modes");
    assert_eq!(
        sparse["rigid_modes"], 3,
        "free assembly: 3 zero modes (sparse)"
    );
    let (a, b) = (
        dense["modes"].as_array().expect("modes"),
        sparse["modes"].as_array().expect("modes"),
    );
    assert_eq!(a.len(), 8, "8 modes reported");
    for (x, y) in a.iter().zip(b) {
        let (fx, fy) = (
            x["frequency_hz"].as_f64().unwrap(),
            y["frequency_hz"].as_f64().unwrap(),
        );
        if x["kind"] == "rigid" {
            assert!(
                x["error_bound"].is_null(),
                "a rigid mode has no error bound"
            );
            continue;
        }
        let bound = x["error_bound"].as_f64().unwrap() + y["error_bound"].as_f64().unwrap();
        let diff = ((fx - fy) / fx).abs();
        assert!(
            diff <= bound,
            "mode {}: dense {fx} Hz, sparse {fy} Hz differ by {diff:.2e}, bounds {bound:.2e}",
            x["index"]
        );
    }
}

/// A reader that closes the pipe early (`| head`) ends the program
/// quietly: exit 0, no panic message.
#[test]
fn a_closed_output_pipe_is_not_a_panic() {
    use std::io::Read;
    use std::process::{Command, Stdio};
    // ~130 kB of JSON: more than a pipe buffers, so the writer sees the close.
    let mut child = Command::new(assert_cmd::cargo::cargo_bin("ancf-modal"))
        .args([
            "transient",
            "models/rcbo_switch_off.json",
            "--from-equilibrium",
        ])
        .args(["--end-time", "3e-3", "--sample-rate", "0", "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0u8; 100];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert!(out.status.success(), "exit {:?}: {err}", out.status.code());
}

#[test]
fn reduce_refuses_more_modes_than_the_fixed_interface_problem_has() {
    // The built-in assembly held at one interface point has far fewer than
    // 500 fixed-interface modes.
    let dir = TempDir::new().expect("a temp dir");
    let (code, stdout, stderr) = run(
        &["reduce", "--interface", "blade:0", "--modes", "500"],
        dir.path(),
    );
    assert_eq!(code, Some(1), "stderr: {stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("--modes `500`") && stderr.contains("at most"),
        "{stderr}"
    );
}
