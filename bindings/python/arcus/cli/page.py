"""The gallery's page: one self-contained HTML file (pictures inlined as data URIs,
tables as text), with the machine, the date and the version it was made with."""

import base64
import datetime
import html
import os
import platform
import shutil
from pathlib import Path

from .. import __version__, devices
from . import resources

STYLE = """body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222;background:#fafafa}
h1{margin-bottom:0}.meta{color:#666}section{margin-top:2em}figure{display:inline-block;vertical-align:top;
margin:0.5em;max-width:520px}figure img{max-width:520px;border:1px solid #ccc}figcaption{font-size:0.9em}
.failed{color:#a00}pre{background:#fff;border:1px solid #ddd;padding:0.5em;overflow-x:auto;font-size:0.8em}"""

# After loading, the page counts its pictures that decoded: the browser test reads it.
CHECK = """window.addEventListener('load',function(){var i=document.images,ok=0;for(var k=0;k<i.length;k++)
{if(i[k].complete&&i[k].naturalWidth>0)ok++;}document.body.setAttribute('data-images',ok+'/'+i.length);});"""


def machine():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    device = ", ".join("%s (%s)" % (d.name, d.version) for d in devices())
    return "%s, %d cores, %s; OpenCL: %s" % (cpu, os.cpu_count() or 0, platform.platform(terse=True), device)


def _image(path):
    data = base64.b64encode(path.read_bytes()).decode()
    return '<img src="data:image/png;base64,%s" alt="%s">' % (data, html.escape(path.name))


def _outputs(root, step):
    """The pictures and tables a step made: those its command names, else every PNG and
    Markdown table in its folder."""
    folder = root / step.out
    if step.pictures:
        return [folder / p for p in step.pictures if (folder / p).is_file()], sorted(folder.glob("*.md"))
    named = [Path(a.replace("{out}", str(folder))) for a in step.argv if "{out}/" in a and a.endswith(".png")]
    if named:
        return [p for p in named if p.is_file()], []
    return sorted(folder.glob("*.png")), sorted(folder.glob("*.md"))


def write(root, steps, seconds, full):
    sections = {}
    for step in steps:
        sections.setdefault(step.section, []).append(step)
    body = []
    for section, members in sections.items():
        body.append("<section><h2>%s</h2>" % html.escape(section))
        for step in members:
            pictures, tables = _outputs(root, step)
            note = ('<p class="failed">failed: %s</p>' % html.escape(step.failed)) if step.failed else ""
            body.append("<figure>%s<figcaption><b>%s</b> (%.0f s). %s%s</figcaption></figure>"
                        % ("".join(_image(p) for p in pictures), html.escape(step.title), step.seconds,
                           html.escape(step.caption), note))
            for t in tables:
                body.append("<details><summary>%s</summary><pre>%s</pre></details>"
                            % (html.escape(t.name), html.escape(t.read_text(errors="replace"))))
        body.append("</section>")
    text = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>arcus %(version)s gallery</title>
<style>%(style)s</style><script>%(check)s</script></head><body>
<h1>arcus %(version)s</h1>
<p class="meta">Light transport in participating media, after the thesis <i>Light Transport in Participating
Media</i>. %(mode)s, made %(date)s in %(seconds).0f s on %(machine)s.</p>
%(body)s
</body></html>
""" % dict(version=html.escape(__version__), style=STYLE, check=CHECK,
           mode="Full settings" if full else "Gallery settings (arcus gallery; --full for the scenes' own)",
           date=datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), seconds=seconds,
           machine=html.escape(machine()), body="\n".join(body))
    index = root / "index.html"
    index.write_text(text)
    return index


def copy_docs_images(root, steps):
    """Copies each engine's picture to docs/images/ of the source tree (the README's)."""
    target = resources.share_dir() / "docs" / "images"
    target.mkdir(parents=True, exist_ok=True)
    for step in steps:
        if step.docs_image and (root / step.docs_image).is_file():
            shutil.copyfile(root / step.docs_image, target / Path(step.docs_image).name)
            print("wrote %s" % (target / Path(step.docs_image).name))
