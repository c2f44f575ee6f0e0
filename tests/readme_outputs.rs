//! The README's example outputs are the binary's (issue 34: an example had
//! gone stale, the switch-off's gravity energy read −8.665e-5 J while a
//! run gives another value). Every fenced block of the README is read for
//! lines `$ ancf-modal …`; each is run (in a fresh directory holding the
//! repository's `models/`, the blocks' commands in order), and the lines
//! shown under it must be the run's output: in order and consecutive,
//! where a line `...` stands for any number of lines. Numbers must match
//! as printed. A command's trailing `# comment` is not run.

use std::path::Path;

use assert_cmd::cargo::cargo_bin_cmd;

/// One `$ ancf-modal` line and the output lines shown under it.
struct Example {
    line: usize,
    args: Vec<String>,
    shown: Vec<String>,
}

/// Splits a command line into words: whitespace separates, double or
/// single quotes group.
fn words(command: &str) -> Vec<String> {
    let (mut out, mut word, mut quote, mut any) = (Vec::new(), String::new(), None, false);
    for c in command.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.push(c),
            (None, '"' | '\'') => {
                quote = Some(c);
                any = true;
            }
            (None, c) if c.is_whitespace() => {
                if any || !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                }
                any = false;
            }
            (None, c) => word.push(c),
        }
    }
    if any || !word.is_empty() {
        out.push(word);
    }
    out
}

/// The README's blocks, each as its examples.
fn examples(readme: &str) -> Vec<Vec<Example>> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<Example>> = None;
    for (i, line) in readme.lines().enumerate() {
        if line.starts_with("```") {
            match current.take() {
                Some(b) => blocks.push(b),
                None => current = Some(Vec::new()),
            }
            continue;
        }
        let Some(block) = current.as_mut() else {
            continue;
        };
        if let Some(command) = line.strip_prefix("$ ancf-modal") {
            let command = command.split(" #").next().unwrap_or("");
            block.push(Example {
                line: i + 1,
                args: words(command),
                shown: Vec::new(),
            });
        } else if let Some(e) = block.last_mut() {
            e.shown.push(line.to_string());
        }
    }
    blocks.into_iter().filter(|b| !b.is_empty()).collect()
}

/// Whether `shown` (with `...` for any lines) is `actual`'s, in order:
/// the first shown line starts anywhere, the next ones follow directly
/// unless a `...` stands between.
fn matches(shown: &[String], actual: &[&str]) -> Result<(), String> {
    let mut at = 0usize;
    let mut free = true;
    for s in shown {
        if s.trim() == "..." {
            free = true;
            continue;
        }
        let found = if free {
            actual[at..]
                .iter()
                .position(|a| a.trim_end() == s.trim_end())
                .map(|k| at + k)
        } else {
            (actual.get(at).map(|a| a.trim_end()) == Some(s.trim_end())).then_some(at)
        };
        match found {
            Some(k) => at = k + 1,
            None => {
                return Err(format!(
                    "`{s}` is not in the output{}",
                    if free {
                        ""
                    } else {
                        " where the README shows it"
                    }
                ))
            }
        }
        free = false;
    }
    Ok(())
}

#[test]
fn the_readme_outputs_are_the_binarys() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let blocks = examples(&readme);
    assert!(blocks.len() >= 4, "the README's examples were not found");
    let mut failures = Vec::new();
    for block in blocks {
        let dir = tempfile::tempdir().unwrap();
        std::os::unix::fs::symlink(root.join("models"), dir.path().join("models")).unwrap();
        for e in block {
            let out = cargo_bin_cmd!("ancf-modal")
                .args(&e.args)
                .current_dir(dir.path())
                .output()
                .unwrap();
            let stdout = String::from_utf8_lossy(&out.stdout);
            if !out.status.success() {
                failures.push(format!(
                    "README.md:{}: exit {:?}: {}",
                    e.line,
                    out.status.code(),
                    String::from_utf8_lossy(&out.stderr)
                ));
                continue;
            }
            let actual: Vec<&str> = stdout.lines().collect();
            if let Err(why) = matches(&e.shown, &actual) {
                failures.push(format!(
                    "README.md:{}: {why}; the run printed:\n{stdout}",
                    e.line
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn the_matcher_holds_order_and_gaps() {
    let actual = ["a", "b", "c", "d"];
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    assert!(matches(&s(&["b", "c"]), &actual).is_ok());
    assert!(matches(&s(&["b", "d"]), &actual).is_err());
    assert!(matches(&s(&["b", "...", "d"]), &actual).is_ok());
    assert!(matches(&s(&["c", "b"]), &actual).is_err());
    assert_eq!(words("a \"b c\" 'd' e"), ["a", "b c", "d", "e"]);
}
