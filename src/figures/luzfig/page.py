"""index.html: every figure with its captions (Portuguese and English), measured numbers,
scene files and commands. Self-contained and offline: inline CSS and script, relative images
and links only. The script writes a status line (every image loaded, no error) into #status,
which the headless-browser test reads back."""

import html
import os

from . import common

STYLE = """
body { font-family: sans-serif; max-width: 1400px; margin: 1em auto; padding: 0 1em;
       color: #222; background: #fafafa; }
figure { margin: 2em 0; padding: 1em; background: white; border: 1px solid #ddd; }
figure img { max-width: 100%; display: block; margin: 0.5em 0; }
figcaption p { margin: 0.4em 0; }
.en { color: #555; }
pre { background: #f3f3f3; padding: 0.5em; overflow-x: auto; font-size: 85%; white-space: pre-wrap; }
table { border-collapse: collapse; font-size: 90%; }
td, th { border: 1px solid #ccc; padding: 2px 6px; text-align: left; }
#status { font-family: monospace; color: #666; }
nav a { margin-right: 0.8em; }
"""

SCRIPT = """
var luzErrors = [];
window.onerror = function (msg) { luzErrors.push(String(msg)); report(); };
function report() {
  var imgs = document.images, bad = [];
  for (var i = 0; i < imgs.length; i++)
    if (!imgs[i].complete || imgs[i].naturalWidth === 0) bad.push(imgs[i].getAttribute('src'));
  var s = document.getElementById('status');
  s.textContent = (bad.length || luzErrors.length ? 'LUZ-STATUS: FAIL' : 'LUZ-STATUS: OK') +
    ' images=' + imgs.length + ' broken=' + bad.length + ' [' + bad.join(' ') + ']' +
    ' errors=' + luzErrors.length + ' [' + luzErrors.join(' | ') + ']';
}
window.addEventListener('load', report);
"""


def _e(s):
    """HTML-escaped text."""
    return html.escape(str(s))


def write(ctx, seconds):
    """Writes OUT/index.html for the figures of `ctx`; `seconds`: how long making them took."""
    parts = ["<!DOCTYPE html>", '<html lang="pt"><head><meta charset="utf-8">',
             "<title>luz — figuras da aula / the lecture's figures</title>",
             f"<style>{STYLE}</style><script>{SCRIPT}</script></head><body>",
             "<h1>Modelos de Iluminação — as figuras da aula, feitas pelo luz</h1>",
             "<p class=en>Illumination models — the lecture's figures, made by luz "
             f"({len(ctx.figures)} figures, {ctx.renders} renders, {seconds:.0f} s). "
             "Every command runs from this folder (the scene files are in "
             "<a href=\"scenes/figures/\">scenes/figures/</a>); commands that write .pfm "
             "also write .png when the extension is changed.</p>",
             '<p id="status">LUZ-STATUS: PENDING</p>', "<nav>"]
    for i, f in enumerate(ctx.figures, 1):
        parts.append(f'<a href="#{_e(f.id)}">{i}. {_e(f.title_pt)}</a>')
    parts.append("</nav>")
    for i, f in enumerate(ctx.figures, 1):
        parts.append(f'<figure id="{_e(f.id)}"><h2>{i}. {_e(f.title_pt)} '
                     f'<span class=en>/ {_e(f.title_en)}</span></h2>')
        for img in f.images:
            parts.append(f'<img src="{_e(img)}" alt="{_e(f.title_en)}">')
        parts.append(f"<figcaption><p>{_e(f.caption_pt)}</p><p class=en>{_e(f.caption_en)}</p>"
                     "</figcaption>")
        if f.numbers:
            parts.append("<table><tr><th>medido / measured</th><th>valor / value</th></tr>")
            for k, v in f.numbers:
                parts.append(f"<tr><td>{_e(k)}</td><td>{_e(v)}</td></tr>")
            parts.append("</table>")
        if f.scenes:
            links = ", ".join(f'<a href="{_e(s)}">{_e(s)}</a>' if not s.startswith("demo:")
                              else _e(s) for s in f.scenes)
            live = [s for s in f.scenes if common.has_web_link(s)]
            if ctx.web and live:  # luz.html beside the page: each scene its URL carries live
                links += " — " + ", ".join(
                    f'<a class="live" href="{_e(common.web_link(ctx, s))}">ao vivo / live</a>'
                    for s in live)
            if ctx.web and len(live) < len(f.scenes):
                links += (" — NFF: abra em luz.html a partir do disco / open it from disk in "
                          '<a href="luz.html">luz.html</a>')
            parts.append(f"<p>Cena / scene: {links}</p>")
        if f.commands:
            parts.append("<pre>" + "\n".join(_e(c) for c in f.commands) + "</pre>")
        parts.append("</figure>")
    parts.append("</body></html>")
    with open(os.path.join(ctx.out, "index.html"), "w", encoding="utf-8") as out:
        out.write("\n".join(parts) + "\n")
