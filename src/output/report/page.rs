//! The page around the sections: head (content security policy, styles),
//! provenance, navigation, and the few lines of script.

use super::svg::escape;
use super::Provenance;
use std::fmt::Write;

/// The content security policy: nothing may be loaded; the page's one
/// stylesheet and one script run, named by their SHA-256 (any other inline
/// style or script is refused too); images only as data. A reference to
/// anything else is refused and reported in the browser's console.
fn csp(style: &str, script: &str) -> String {
    format!(
        "default-src 'none'; style-src '{}'; script-src '{}'; img-src data:",
        source_hash(style),
        source_hash(script)
    )
}

/// A CSP hash source: `sha256-` and the base64 of the text's SHA-256.
fn source_hash(text: &str) -> String {
    use base64::Engine;
    use sha2::{Digest, Sha256};
    let digest = Sha256::digest(text.as_bytes());
    format!(
        "sha256-{}",
        base64::engine::general_purpose::STANDARD.encode(digest)
    )
}

const STYLE: &str = r#"
:root { color-scheme: light; --ink: #222; --grey: #999; --accent: #0072b2; }
* { box-sizing: border-box; }
body { font: 15px/1.45 system-ui, sans-serif; color: var(--ink); margin: 0 auto; padding: 0 1rem 3rem; max-width: 1180px; }
header { border-bottom: 1px solid #ddd; margin-bottom: 1rem; }
h1 { font-size: 1.5rem; margin: 1rem 0 0.3rem; }
.warnings { border-left: 4px solid #d55e00; padding-left: 0.8rem; }
h2 { font-size: 1.2rem; margin-top: 2rem; border-bottom: 1px solid #eee; }
dl.provenance { display: grid; grid-template-columns: max-content minmax(0, 1fr); gap: 0.1rem 1rem; font-size: 0.85rem; }
dl.provenance dd { margin: 0; overflow-wrap: anywhere; }
nav ul { list-style: none; padding: 0; display: flex; flex-wrap: wrap; gap: 0.3rem 1rem; }
nav a { color: var(--accent); }
table { border-collapse: collapse; margin: 0.8rem 0; font-size: 0.9rem; display: block; max-width: 100%; overflow-x: auto; }
th, td { padding: 0.2rem 0.6rem; border-bottom: 1px solid #eee; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
caption { text-align: left; font-weight: 600; padding-bottom: 0.3rem; }
svg { max-width: 100%; height: auto; }
svg.assembly { display: block; margin: 0 auto; }
pre { font-size: 0.8rem; overflow-x: auto; max-width: 100%; background: #f8f8f8; padding: 0.5rem; }
.mode-grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(260px, 1fr)); gap: 1rem; }
figure { margin: 0; }
figure.mode { border: 1px solid #eee; padding: 0.3rem; }
figure.mode svg { width: 100%; }
figcaption { font-size: 0.9rem; text-align: center; }
.undeformed polyline { fill: none; stroke: #bbb; stroke-width: 1.5; }
.undeformed .body { fill: #ccc; fill-opacity: 0.6; stroke: #bbb; }
.undeformed .joint { fill: #fff; stroke: #999; }
.undeformed .weld { fill: #999; }
.deformed polyline { fill: none; stroke: var(--accent); stroke-width: 2.2; }
.deformed .body { fill: var(--accent); fill-opacity: 0.45; stroke: var(--accent); }
.deformed .joint { fill: #fff; stroke: var(--accent); }
.deformed .weld { fill: var(--accent); }
.undeformed .link, .deformed .link { fill: none; stroke-width: 5; stroke-linecap: round; }
.undeformed .spring, .deformed .spring { fill: none; stroke: #009e73; stroke-width: 1.2; }
.undeformed .rail, .deformed .rail { fill: none; stroke: #555; stroke-width: 2; }
.undeformed .ground, .deformed .ground { fill: #fff; stroke: #555; stroke-width: 1.2; }
.undeformed .hatch, .deformed .hatch { fill: none; stroke: #777; stroke-width: 1; }
.still { display: none; }
.contact { fill: #d55e00; }
.load { stroke: #cc79a7; stroke-width: 2; }
marker path { fill: #cc79a7; }
.sensor { fill: none; stroke: #e69f00; stroke-width: 2; }
.scalebar line { stroke: var(--ink); stroke-width: 2; }
.scalebar text { font-size: 11px; fill: var(--ink); }
.controls { display: flex; flex-wrap: wrap; gap: 0.5rem 1.2rem; align-items: center; margin: 0.5rem 0; }
.note { font-size: 0.85rem; color: #555; }
@media (prefers-reduced-motion: reduce) { .anim { display: none; } .still { display: inline; } }
@media print {
  .anim, .controls, nav { display: none; }
  .still { display: inline; }
  figure.mode, figure.plot, table { break-inside: avoid; }
  body { max-width: none; }
}
"#;

/// Mode picker, amplitude slider and play/pause; `#freeze=P` in the
/// address pauses every animation at phase P of its period, drawing each
/// mode at cos 2πP of its amplitude (0 and 1 the largest deflection, 0.5
/// the opposite one, 0.25 and 0.75 the undeformed pass; a link to one
/// frame, and what the browser checks use), `#probe` appends the page's
/// layout as JSON in a hidden `<pre id="probe">` (the browser checks read
/// it from the DOM). Without script the page works the same, animated by
/// SMIL.
const SCRIPT: &str = r#"
(function () {
  var svgs = Array.prototype.slice.call(document.querySelectorAll('svg.mode-shape'));
  var period = PERIOD;
  function seek(phase) { svgs.forEach(function (s) { s.pauseAnimations(); s.setCurrentTime(phase * period); }); }
  var m = /freeze=([0-9.]+)/.exec(location.hash);
  if (m) { seek(parseFloat(m[1])); }
  if (/probe/.test(location.hash)) { probe(); }
  document.querySelectorAll('.controls').forEach(function (c) { c.hidden = false; });
  var play = document.getElementById('play');
  if (play) {
    play.addEventListener('click', function () {
      var paused = svgs.length > 0 && svgs[0].animationsPaused();
      svgs.forEach(function (s) { if (paused) { s.unpauseAnimations(); } else { s.pauseAnimations(); } });
      play.textContent = paused ? 'Pause' : 'Play';
    });
  }
  var pick = document.getElementById('pick');
  if (pick) {
    pick.addEventListener('change', function () {
      document.querySelectorAll('figure.mode').forEach(function (f) {
        f.hidden = pick.value !== 'all' && f.getAttribute('data-mode') !== pick.value;
      });
    });
  }
  var amp = document.getElementById('amplitude');
  if (amp) {
    var anims = Array.prototype.slice.call(document.querySelectorAll('.anim animate'));
    anims.forEach(function (a) { a.setAttribute('data-values', a.getAttribute('values')); });
    amp.addEventListener('input', function () {
      var k = parseFloat(amp.value);
      svgs.forEach(function (s) {
        var base = s.querySelector('.undeformed');
        var anim = s.querySelectorAll('.anim animate');
        anim.forEach(function (a) { a.setAttribute('values', scale(a, k, base)); });
      });
    });
  }
  function probe() {
    var rect = function (e) { var r = e.getBoundingClientRect(); return [r.left + scrollX, r.top + scrollY, r.width, r.height]; };
    var out = {
      width: innerWidth,
      scroll_width: document.documentElement.scrollWidth,
      height: document.documentElement.scrollHeight,
      panels: Array.prototype.map.call(document.querySelectorAll('figure.mode svg'), rect),
      sections: Array.prototype.map.call(document.querySelectorAll('main section'), function (s) { return s.id; })
    };
    var pre = document.createElement('pre');
    pre.id = 'probe';
    pre.hidden = true;
    pre.textContent = JSON.stringify(out);
    document.body.appendChild(pre);
  }
  function scale(a, k, base) {
    var el = a.parentNode, group = el.parentNode;
    var index = Array.prototype.indexOf.call(group.children, el);
    var ref = base.children[index];
    var attr = a.getAttribute('attributeName');
    var rest = attr === 'points' ? ref.getAttribute('points') : ref.getAttribute(attr);
    var r = rest.split(/[ ,]+/).map(parseFloat);
    return a.getAttribute('data-values').split(';').map(function (frame) {
      var v = frame.split(/[ ,]+/).map(parseFloat);
      var out = v.map(function (x, i) { return (r[i] + k * (x - r[i])).toFixed(2); });
      if (attr !== 'points') { return out[0]; }
      var pairs = [];
      for (var i = 0; i + 1 < out.length; i += 2) { pairs.push(out[i] + ',' + out[i + 1]); }
      return pairs.join(' ');
    }).join(';');
  }
})();
"#;

/// The whole document around `body`; `modes`: the numbers of the
/// animated modes (the picker's choices).
pub fn document(p: &Provenance, nav: &[(String, String)], modes: &[usize], body: &str) -> String {
    let script = SCRIPT.replace("PERIOD", &super::animate::PERIOD_S.to_string());
    let csp = csp(STYLE, &script);
    let mut s = String::with_capacity(body.len() + 8192);
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><meta http-equiv=\"Content-Security-Policy\" content=\"{csp}\"><title>ancf-modal report: {}</title><style>{STYLE}</style></head><body><header><h1>Modal report: {}</h1><dl class=\"provenance\"><dt>tool</dt><dd>ancf-modal {}</dd><dt>model</dt><dd>{}</dd><dt>model SHA-256</dt><dd><code>{}</code></dd><dt>command</dt><dd><code>{}</code></dd><dt>written</dt><dd>{}</dd></dl><nav><ul>",
        escape(&p.model_name),
        escape(&p.model_name),
        escape(&p.tool_version),
        escape(&p.model_name),
        escape(&p.model_sha256),
        escape(&p.command_line),
        escape(&p.date),
    );
    for (id, title) in nav {
        let _ = write!(
            s,
            "<li><a href=\"#{}\">{}</a></li>",
            escape(id),
            escape(title)
        );
    }
    s.push_str("</ul></nav><div class=\"controls\" hidden><label>mode <select id=\"pick\"><option value=\"all\">all</option>");
    for n in modes {
        let _ = write!(s, "<option value=\"{n}\">{n}</option>");
    }
    s.push_str("</select></label><label>amplitude <input id=\"amplitude\" type=\"range\" min=\"0\" max=\"2\" step=\"0.05\" value=\"1\"></label><button id=\"play\" type=\"button\">Pause</button><span class=\"note\">A link ending in #freeze=P shows phase P: each shape at cos 2πP of its amplitude (0 the largest deflection, 0.25 none).</span></div></header><main>");
    s.push_str(body);
    let _ = writeln!(s, "</main><script>{script}</script></body></html>");
    s
}
