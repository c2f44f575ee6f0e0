//! The library's folders form an order without cycles (README, Layout):
//!
//!   error → model → linalg, mechanics, signal → system → measured
//!         → analysis → results → output → cli
//!
//! A file in one folder may name (`crate::FOLDER`) only folders before its
//! own; `error.rs` names none. Doc comments are left out (a link is not a
//! dependency). Checked on the source text, so a new import that closes a
//! circle fails here with the file and the line.

use std::path::{Path, PathBuf};

/// The folders in order; folders of one rank may not name each other.
const ORDER: &[&[&str]] = &[
    &["error"],
    &["model"],
    &["linalg", "mechanics", "signal"],
    &["system"],
    &["measured"],
    &["analysis"],
    &["results"],
    &["output"],
    &["cli"],
];

fn rank(folder: &str) -> Option<usize> {
    ORDER.iter().position(|r| r.contains(&folder))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The crate folders a line of code names (`crate::X`), comments left out.
fn named(line: &str) -> Vec<&str> {
    let code = line.split("//").next().unwrap_or("");
    code.match_indices("crate::")
        .filter_map(|(i, _)| {
            let rest = &code[i + "crate::".len()..];
            let end = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            let name = &rest[..end];
            rank(name).map(|_| name)
        })
        .collect()
}

#[test]
fn folders_name_only_the_folders_before_them() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut offences = Vec::new();
    let mut checked = 0;
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let top = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let own = top.trim_end_matches(".rs");
        let Some(own_rank) = rank(own) else {
            continue; // lib.rs, main.rs
        };
        checked += 1;
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in text.lines().enumerate() {
            for other in named(line) {
                if other != own && rank(other).unwrap() >= own_rank {
                    offences.push(format!(
                        "src/{}:{}: {own} names {other}",
                        rel.display(),
                        n + 1
                    ));
                }
            }
        }
    }
    assert!(checked > 100, "only {checked} files checked");
    assert!(offences.is_empty(), "{}", offences.join("\n"));
}

#[test]
fn a_line_names_the_folders_of_its_code_not_of_its_comments() {
    assert_eq!(
        named("use crate::model::Model; // crate::output"),
        vec!["model"]
    );
    assert_eq!(named("/// [`crate::output::x`]"), Vec::<&str>::new());
    assert_eq!(
        named("let a = crate::analysis::f(crate::system::g());"),
        vec!["analysis", "system"]
    );
}
