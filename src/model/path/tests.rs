//! Properties of the one parameter-path module over the shipped models and
//! the built-in: every spelling of a number reads the same value, writes
//! give the same model either way, and errors list what is allowed.

use super::*;
use crate::error::Source;

/// The built-in models and every model file of `models/`.
fn models() -> Vec<(String, Model)> {
    let mut out = vec![
        (String::from("builtin"), Model::builtin().into_model()),
        (
            String::from("switch_off"),
            Model::switch_off_builtin().into_model(),
        ),
    ];
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let m = Model::from_json(&text, Source::File(f.clone()))
            .unwrap()
            .into_model();
        out.push((f.display().to_string(), m));
    }
    assert!(out.len() > 3, "the shipped models are found");
    out
}

/// The spellings of one short name `ID.PROP`: `ID.GROUP.PROP`, and the
/// JSON path by index and (where the element has an id) by id.
fn spellings(name: &str, target: Target) -> Vec<String> {
    let p = target.property();
    let (id, _) = name.rsplit_once('.').unwrap();
    let by_index = target.path().to_string();
    let mut out = vec![name.to_string(), by_index.clone()];
    if let Some(g) = p.group {
        out.push(format!("{id}.{g}.{}", p.name));
    }
    // `joints[1]`, `springs[0]`: an element without an id.
    if !id.contains('[') {
        let (open, close) = (by_index.find('[').unwrap(), by_index.find(']').unwrap());
        out.push(format!(
            "{}[{id}]{}",
            &by_index[..open],
            &by_index[close + 1..]
        ));
    }
    out
}

#[test]
fn every_spelling_of_a_short_name_reads_the_same_number() {
    for (file, m) in models() {
        let json = serde_json::to_value(&m).unwrap();
        for name in available_names(&m) {
            let (canonical, target) = resolve_short(&m, &name).expect(&name);
            assert_eq!(canonical, name, "{file}");
            for spelling in spellings(&name, target) {
                let path = NumberPath::resolve(&m, &json, &spelling)
                    .unwrap_or_else(|e| panic!("{file}: {spelling}: {e}"));
                assert_eq!(path, target.path(), "{file}: {spelling}");
            }
            let typed = target.get(&m);
            match target.path().number(&json) {
                Some(v) => assert_eq!(v.to_bits(), typed.to_bits(), "{file}: {name}"),
                // Only an absent torsion spring has no number; it reads 0.
                None => assert_eq!(typed, 0.0, "{file}: {name}"),
            }
        }
    }
}

#[test]
fn setting_by_short_name_or_by_path_gives_the_same_model() {
    for (file, m) in models() {
        let json = serde_json::to_value(&m).unwrap();
        for name in available_names(&m) {
            let (_, target) = resolve_short(&m, &name).unwrap();
            let value = 1.37 * target.get(&m) + 0.25;
            let mut typed = m.clone();
            target.set(&mut typed, value);
            assert_eq!(target.get(&typed).to_bits(), value.to_bits(), "{name}");
            let path = NumberPath::resolve(&m, &json, &target.path().to_string()).unwrap();
            let mut written = json.clone();
            assert!(path.set(&mut written, Value::from(value)), "{file}: {name}");
            assert_eq!(path.number(&written), Some(value), "{file}: {name}");
            let parsed: Model = serde_json::from_value(written).unwrap();
            assert_eq!(parsed, typed, "{file}: {name}");
        }
    }
}

#[test]
fn a_missing_optional_key_is_added_when_written() {
    // The built-in's pin between pad and blade has no torsion spring.
    let m = Model::builtin();
    let j = (m.joints.iter())
        .position(|j| j.id.as_deref() == Some("pad_pin") && j.torsion_stiffness.is_none())
        .expect("the built-in has a free pin `pad_pin`");
    let json = serde_json::to_value(&m).unwrap();
    let path = NumberPath::resolve(&m, &json, "pad_pin.torsion_stiffness").unwrap();
    assert_eq!(path.to_string(), format!("joints[{j}].torsion_stiffness"));
    assert_eq!(path.get(&json), None);
    let mut written = json.clone();
    assert!(path.set(&mut written, Value::from(2.5e-3)));
    let parsed: Model = serde_json::from_value(written).unwrap();
    assert_eq!(parsed.joints[j].torsion_stiffness, Some(2.5e-3));
}

#[test]
fn an_unknown_name_lists_the_allowed_names() {
    for (file, m) in models() {
        let json = serde_json::to_value(&m).unwrap();
        let allowed = available_names(&m);
        match resolve_short(&m, "blade.colour") {
            Err(PathError::UnknownShortName { available, .. }) => assert_eq!(available, allowed),
            other => panic!("{file}: {other:?}"),
        }
        let e = NumberPath::resolve(&m, &json, "colour").unwrap_err();
        match &e {
            PathError::Unknown { short_names, .. } => assert_eq!(short_names, &allowed),
            other => panic!("{file}: {other:?}"),
        }
        let text = e.to_string();
        assert_eq!(text.lines().count(), 1);
        assert!(allowed.iter().all(|n| text.contains(n.as_str())), "{text}");
    }
}

#[test]
fn bad_paths_say_what_is_there() {
    let m = Model::builtin();
    let json = serde_json::to_value(&m).unwrap();
    let resolve = |name: &str| NumberPath::resolve(&m, &json, name);
    match resolve("mass") {
        Err(PathError::Ambiguous { candidates, .. }) => {
            assert!(candidates.len() > 1);
            for c in candidates {
                assert!(resolve_short(&m, &c).is_ok(), "{c}");
            }
        }
        other => panic!("{other:?}"),
    }
    match resolve("beams[wing].section.height") {
        Err(PathError::NotFound {
            path, available, ..
        }) => {
            assert_eq!(path, "beams[wing]");
            assert_eq!(available, vec![format!("[{}]", m.beams[0].id)]);
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        resolve("beams[0].section"),
        Err(PathError::NotNumeric { .. })
    ));
    assert!(matches!(
        resolve("beams[0].id"),
        Err(PathError::NotNumeric { .. })
    ));
    assert!(matches!(
        resolve("beams[0.height"),
        Err(PathError::Syntax { .. })
    ));
    let colour = resolve("beams[0].colour").unwrap();
    assert!(matches!(
        colour.check_settable(&json, "beams[0].colour", Value::from(1.0)),
        Err(PathError::NotSettable { .. })
    ));
    let count = resolve("beams[0].elements").unwrap();
    assert!(count
        .check_settable(&json, "beams[0].elements", Value::from(4))
        .is_ok());
    assert!(count
        .check_settable(&json, "beams[0].elements", Value::from(4.5))
        .is_err());
}

#[test]
fn the_pointer_escapes_keys() {
    let p = NumberPath::new(vec![
        Step::Key(String::from("a/b")),
        Step::Index(3),
        Step::Key(String::from("c~d")),
    ]);
    assert_eq!(p.pointer(), "/a~1b/3/c~0d");
    assert_eq!(p.to_string(), "a/b[3].c~d");
}

#[test]
fn every_target_has_a_unit_from_the_table() {
    let m = Model::builtin();
    for name in available_names(&m) {
        let (_, t) = resolve_short(&m, &name).unwrap();
        assert!(PROPERTIES.contains(t.property()));
        assert!(!t.unit().is_empty());
    }
}

#[test]
fn short_names_resolve_in_all_spellings() {
    let m = Model::builtin();
    for n in [
        "height",
        "blade.height",
        "section.height",
        "blade.section.height",
    ] {
        let (name, t) = resolve_short(&m, n).expect(n);
        assert_eq!(name, "blade.height");
        assert_eq!(t, Target::BeamHeight(0));
    }
    assert_eq!(
        resolve_short(&m, "blade.material.young").unwrap().1,
        Target::BeamYoung(0)
    );
    assert_eq!(
        resolve_short(&m, "pad.mass").unwrap().1,
        Target::PointMass(0)
    );
    assert_eq!(
        resolve_short(&m, "inertia").unwrap().1,
        Target::RigidInertia(0)
    );
    assert!(matches!(
        resolve_short(&m, "mass"),
        Err(PathError::Ambiguous { .. })
    ));
    assert!(matches!(
        resolve_short(&m, "blade.colour"),
        Err(PathError::UnknownShortName { .. })
    ));
    assert!(matches!(
        resolve_short(&m, "wing.height"),
        Err(PathError::UnknownShortName { .. })
    ));
}
