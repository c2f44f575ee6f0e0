//! The HTML report in a real browser: Debian's headless Chromium.
//!
//! - no console message at all (a blocked load, a script error or a
//!   content-security-policy violation each print one) and no network
//!   request of the page in Chromium's net log;
//! - with the animations paused at phase 0 and at half the period
//!   (`#freeze=`), the two screenshots differ inside the mode panels and
//!   are pixel-identical outside them; phases of equal cos 2πP (0.25 and
//!   0.75, 0.125 and 0.875) draw alike, and 0.25 (zero amplitude) differs
//!   from 0 in every panel;
//! - no horizontal overflow at 1280 px and at 400 px;
//! - printed to PDF, with JavaScript and without, every section's title
//!   and every mode's caption is on a page (pdftotext), and every page
//!   renders (pdftoppm).
//!
//! `.ci/run` installs Chromium when it is missing and sets CI=true; then a
//! missing browser fails the test. Elsewhere the test says that it was
//! skipped and why.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

/// The browser, or `None` (with the reason printed) when it is missing
/// outside CI.
fn chromium() -> Option<PathBuf> {
    let path =
        PathBuf::from(std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into()));
    if path.exists() {
        return Some(path);
    }
    let why = format!(
        "{} not found: install Debian's `chromium` and `poppler-utils` (`.ci/run` does)",
        path.display()
    );
    if std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("{why}");
    }
    eprintln!("SKIPPED: the browser checks of the report: {why}");
    None
}

struct Browser {
    exe: PathBuf,
    dir: tempfile::TempDir,
}

impl Browser {
    fn command(&self, width: u32, height: u32, extra: &[&str]) -> Command {
        let mut c = Command::new(&self.exe);
        c.args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            "--enable-logging=stderr",
            "--v=0",
        ]);
        c.arg(format!(
            "--user-data-dir={}",
            self.dir.path().join("profile").display()
        ));
        c.arg(format!("--window-size={width},{height}"));
        c.args(extra);
        c
    }

    /// The DOM after the scripts ran, and the console lines.
    fn dump(&self, url: &str, width: u32, extra: &[&str]) -> (String, Vec<String>) {
        let mut args = vec!["--dump-dom"];
        args.extend(extra);
        let out = self
            .command(width, 900, &args)
            .arg(url)
            .output()
            .expect("chromium runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (
            String::from_utf8_lossy(&out.stdout).into_owned(),
            console_lines(&out.stderr),
        )
    }

    fn screenshot(&self, url: &str, width: u32, height: u32, name: &str) -> (u32, Vec<u8>) {
        let file = self.dir.path().join(name);
        let shot = format!("--screenshot={}", file.display());
        let out = self
            .command(width, height, &[shot.as_str()])
            .arg(url)
            .output()
            .expect("chromium runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(console_lines(&out.stderr).is_empty());
        let bytes = std::fs::read(&file).unwrap();
        let mut reader = png::Decoder::new(bytes.as_slice()).read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        let channels = info.color_type.samples();
        let rgb: Vec<u8> = buf[..info.buffer_size()]
            .chunks(channels)
            .flat_map(|p| p[..3].to_vec())
            .collect();
        (info.width, rgb)
    }
}

fn console_lines(stderr: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stderr)
        .lines()
        .filter(|l| l.contains(":CONSOLE"))
        .map(String::from)
        .collect()
}

/// The URLs the page asked for, from Chromium's net log: requests whose
/// initiator is the page (a file's origin is `null`); the browser's own
/// background requests say "not an origin".
fn page_requests(netlog: &Path) -> Vec<String> {
    let log: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(netlog).unwrap()).unwrap();
    log["events"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|e| {
            let p = &e["params"];
            let initiator = p["initiator"].as_str()?;
            (initiator != "not an origin").then(|| format!("{initiator} → {}", p["url"]))
        })
        .collect()
}

#[derive(serde::Deserialize)]
struct Probe {
    width: f64,
    scroll_width: f64,
    height: f64,
    panels: Vec<[f64; 4]>,
    sections: Vec<String>,
}

fn probe(dom: &str) -> Probe {
    let start = dom
        .find("<pre id=\"probe\" hidden=\"\">")
        .expect("the probe ran");
    let text = &dom[start..];
    let text = &text[text.find('>').unwrap() + 1..text.find("</pre>").unwrap()];
    serde_json::from_str(&text.replace("&quot;", "\"").replace("&amp;", "&")).unwrap()
}

fn url(path: &Path, hash: &str) -> String {
    format!("file://{}#{hash}", path.display())
}

#[test]
fn the_report_works_in_a_real_browser() {
    let Some(exe) = chromium() else { return };
    let browser = Browser {
        exe,
        dir: tempfile::tempdir().unwrap(),
    };
    let page = browser.dir.path().join("report.html");
    common::run_ok(["report", "--out", page.to_str().unwrap()]);
    let html = std::fs::read_to_string(&page).unwrap();

    // No console message, no network request.
    let netlog = browser.dir.path().join("net.json");
    let log = format!("--log-net-log={}", netlog.display());
    let (dom, console) = browser.dump(&url(&page, "probe"), 1280, &[log.as_str()]);
    assert!(console.is_empty(), "console: {console:#?}");
    assert_eq!(
        page_requests(&netlog),
        Vec::<String>::new(),
        "network requests of the page"
    );

    // The modes table's frequencies, as the browser holds them, are
    // `modal --json`'s to the last digit.
    let shown: Vec<f64> = dom
        .split("data-frequency-hz=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap().parse().unwrap())
        .collect();
    let modal: serde_json::Value = serde_json::from_slice(&common::run_ok([
        "modal",
        "--modes",
        &shown.len().to_string(),
        "--json",
    ]))
    .unwrap();
    let want: Vec<f64> = modal["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["frequency_hz"].as_f64().unwrap())
        .collect();
    assert_eq!(shown, want);

    // No horizontal overflow.
    let wide = probe(&dom);
    assert!(
        wide.scroll_width <= wide.width,
        "1280 px: {} wide",
        wide.scroll_width
    );
    let (narrow_dom, console) = browser.dump(&url(&page, "probe"), 400, &[]);
    assert!(console.is_empty(), "console at 400 px: {console:#?}");
    let narrow = probe(&narrow_dom);
    assert!(
        narrow.scroll_width <= narrow.width,
        "400 px: {} wide",
        narrow.scroll_width
    );

    // Paused at phase 0 and at half the period: the frames differ inside
    // the mode panels only.
    assert!(!wide.panels.is_empty());
    let height = wide.height.ceil() as u32;
    let (w, a) = browser.screenshot(&url(&page, "freeze=0"), 1280, height, "a.png");
    let (_, b) = browser.screenshot(&url(&page, "freeze=0.5"), 1280, height, "b.png");
    assert_eq!(a.len(), b.len());
    let inside = |x: f64, y: f64| {
        wide.panels.iter().position(|r| {
            x >= r[0] - 1.0 && x <= r[0] + r[2] + 1.0 && y >= r[1] - 1.0 && y <= r[1] + r[3] + 1.0
        })
    };
    let mut changed = vec![0usize; wide.panels.len()];
    for (i, (pa, pb)) in a.chunks(3).zip(b.chunks(3)).enumerate() {
        if pa != pb {
            let (x, y) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
            match inside(x, y) {
                Some(k) => changed[k] += 1,
                None => panic!("pixel ({x}, {y}) changed outside the mode panels"),
            }
        }
    }
    assert!(
        changed.iter().all(|&c| c > 0),
        "pixels changed per panel: {changed:?}"
    );
    // `#freeze=P` is phase P of cos 2πP: the shapes at 0.25 and 0.75 (both
    // at zero amplitude) and at 0.125 and 0.875 (both at cos π/4, frames of the
    // animation) are drawn
    // alike, pixel for pixel; 0.25 differs from 0 in every panel.
    let (_, quarter) = browser.screenshot(&url(&page, "freeze=0.25"), 1280, height, "c.png");
    let (_, three) = browser.screenshot(&url(&page, "freeze=0.75"), 1280, height, "d.png");
    assert!(quarter == three, "freeze=0.25 and 0.75 draw differently");
    let (_, tenth) = browser.screenshot(&url(&page, "freeze=0.125"), 1280, height, "e.png");
    let (_, ninth) = browser.screenshot(&url(&page, "freeze=0.875"), 1280, height, "f.png");
    assert!(tenth == ninth, "freeze=0.125 and 0.875 draw differently");
    let mut flat = vec![0usize; wide.panels.len()];
    for (i, (pa, pq)) in a.chunks(3).zip(quarter.chunks(3)).enumerate() {
        if pa != pq {
            let (x, y) = ((i as u32 % w) as f64 + 0.5, (i as u32 / w) as f64 + 0.5);
            if let Some(k) = inside(x, y) {
                flat[k] += 1;
            }
        }
    }
    assert!(
        flat.iter().all(|&c| c > 0),
        "freeze=0 against 0.25 per panel: {flat:?}"
    );

    // Printed, with and without JavaScript: every section's title and
    // every mode's caption on a page.
    let titles: Vec<&str> = html
        .split("<h2>")
        .skip(1)
        .map(|s| s.split("</h2>").next().unwrap())
        .collect();
    assert_eq!(titles.len(), wide.sections.len());
    let captions: Vec<&str> = html
        .split("<figcaption>")
        .skip(1)
        .map(|s| s.split("</figcaption>").next().unwrap())
        .collect();
    assert_eq!(captions.len(), wide.panels.len());
    let pdf = browser.dir.path().join("report.pdf");
    for script in ["", "--blink-settings=scriptEnabled=false"] {
        let print = format!("--print-to-pdf={}", pdf.display());
        let mut args = vec![print.as_str(), "--no-pdf-header-footer"];
        if !script.is_empty() {
            args.push(script);
        }
        let out = browser
            .command(1280, 900, &args)
            .arg(url(&page, ""))
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let console = console_lines(&out.stderr);
        assert!(console.is_empty(), "console ({script}): {console:#?}");
        let text = Command::new("pdftotext")
            .arg(&pdf)
            .arg("-")
            .output()
            .expect("pdftotext (poppler-utils)");
        let text = String::from_utf8_lossy(&text.stdout).replace('\u{a0}', " ");
        for t in titles.iter().chain(&captions) {
            let t = t
                .replace("&#39;", "'")
                .replace("&quot;", "\"")
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
            assert!(text.contains(&t), "printed page ({script}) lacks `{t}`");
        }
    }
    let pages = browser.dir.path().join("page");
    let st = Command::new("pdftoppm")
        .args(["-r", "30", "-png"])
        .arg(&pdf)
        .arg(&pages)
        .status()
        .expect("pdftoppm (poppler-utils)");
    assert!(st.success());
    let rendered = std::fs::read_dir(browser.dir.path())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with("page")
        })
        .count();
    assert!(rendered >= 1);
}
