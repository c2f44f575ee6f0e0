//! `ancf-modal` command line: parse, validate, run, print.

mod cli;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    if let Err(e) = cli::run(args) {
        eprintln!("Error: {}", one_line(&e));
        std::process::exit(1);
    }
}

/// The error and its causes on one line, `a: b: c`, leaving out a cause
/// whose text the line already holds (library errors that wrap another
/// print it in their own message).
fn one_line(e: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}
