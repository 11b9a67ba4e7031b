#!/usr/bin/env python3
"""Renders a report.html in headless Chromium and checks the rendered DOM (and, with a measuring
script in a copy of the page, its layout).

    check_report_in_browser.py CHROMIUM REPORT_DIR SCREENSHOT.png

REPORT_DIR holds report.json and report.html. From Chromium's --dump-dom
(the DOM after layout, not the file as written) it checks that every claim of
report.json has exactly one findings row (data-claim-row) and one plot
(data-claim-plot, an <svg> with plotted points), that every claim with
evidence "h_max_by_speed" has one map of h_max against |w| (data-claim-map, with
points) and no other claim has one, that every verdict is shown, the work-precision diagrams
(both axes whenever their data exist, a program's map named where its evaluations are unknown,
hover texts with exponents and units, captions in words), the baseline's errors beside compared
series, no "max error 0" for what was not measured, no verdict badge outside its cell,
and that the page loads nothing from the network. It then saves a screenshot
of the top of the page. Exit 0 on success, 1 on a failed check, 77 (ctest's
skip code here) when CHROMIUM is not installed.
"""
import html
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def chromium(binary, arguments):
    with tempfile.TemporaryDirectory(prefix="vivv-chromium-") as profile:
        result = subprocess.run([binary, *FLAGS, f"--user-data-dir={profile}", *arguments],
                                capture_output=True, text=True, timeout=180)
    if result.returncode != 0:
        sys.stderr.write(result.stderr)
        raise SystemExit(f"chromium exited with {result.returncode}")
    return result.stdout


def attribute_values(dom, name):
    return Counter(html.unescape(v) for v in re.findall(rf'{name}="([^"]*)"', dom))


def check_evidence_figures(report, dom, evidence, attribute, svg_class, mark, what, problems):
    """One figure `what` (an <svg class=SVG_CLASS ATTRIBUTE=KEY>) with at least one MARK for every
    claim whose evidence has EVIDENCE, none for the others, and no NaN or infinity in any."""
    keys = [f"{case['name']}/{claim['id']}" for case in report["cases"] for claim in case["claims"]
            if isinstance(claim.get("evidence"), dict) and claim["evidence"].get(evidence)]
    shown = attribute_values(dom, attribute)
    for key in keys:
        if shown[key] != 1:
            problems.append(f"{key}: {shown[key]} {what}, expected 1")
    for key in set(shown) - set(keys):
        problems.append(f"{key}: {what} for a claim without {evidence}")
    for match in re.finditer(rf'<svg class="{svg_class}"[^>]*{attribute}="([^"]*)"[^>]*>(.*?)</svg>', dom, re.S):
        if f"{mark}=" not in match.group(2):
            problems.append(f"{html.unescape(match.group(1))}: {what} without {mark}")
        if re.search(r'="[^"]*\b(nan|inf)\b', match.group(2)):
            problems.append(f"{html.unescape(match.group(1))}: NaN or infinity in the {what}")
    return keys, shown


def problem_key(case):
    return f"{case['system']} {json.dumps(case.get('parameters'))} {json.dumps(case['initial'])} {case.get('T')}"


def check_work_precision(report, dom, problems):
    """A diagram on each axis for each group of two or more cases of one system, parameters,
    initial state and T with a global-order claim, when one of them has that cost (a program's map
    has wall time but no counted evaluations: it is named in the evaluations caption instead);
    hover texts with the error's exponent and the axis's unit; captions in words, not JSON."""
    members = {}
    for case in report["cases"]:
        if any(claim["id"] == "global-order" and claim.get("series") for claim in case["claims"]):
            members.setdefault(problem_key(case), []).append(case)
    seconds = report["run"].get("run_seconds", {})
    counted = lambda case: any(isinstance(row.get("L_evaluations"), int) and row["L_evaluations"] > 0  # noqa: E731
                               for row in case.get("cost", []))
    timed = lambda case: any(row.get("seconds", 0) > 0 for row in seconds.get(case["name"], []))  # noqa: E731
    for axis, has_cost in (("evaluations", counted), ("seconds", timed)):
        expected = sum(1 for cases in members.values() if len(cases) >= 2 and any(map(has_cost, cases)))
        figures = re.findall(rf'<figure class="work-precision"><svg[^>]*data-work-precision="{axis}-\d+"(.*?)</figure>',
                             dom, re.S)
        if len(figures) != expected:
            problems.append(f"{len(figures)} work-precision diagrams against {axis}, expected {expected}")
        unit = r"\d+ evaluations of L" if axis == "evaluations" else r"[0-9.e+-]+ s of wall time"
        for figure in figures:
            for title in re.findall(r"<circle[^>]*><title>(.*?)</title>", figure, re.S):
                title = html.unescape(title)
                match = re.fullmatch(r"(.+), N = (\d+): error (\S+), (.+)", title)
                if not match or not re.fullmatch(unit, match.group(4)):
                    problems.append(f"work-precision ({axis}) hover text {title!r}: not 'CASE, N = n: error E, {unit}'")
                    continue
                case = next((c for c in report["cases"] if c["name"] == match.group(1)), None)
                claim = next((cl for cl in case["claims"] if cl["id"] == "global-order"), None) if case else None
                steps = case.get("sweep", {}).get("steps_used", []) if case else []
                n = int(match.group(2))
                if not claim or n not in steps:
                    problems.append(f"work-precision hover text {title!r} names no point of report.json")
                    continue
                error = float(claim["series"][0]["error"][steps.index(n)])
                if abs(float(match.group(3)) - error) > 1e-3 * abs(error):
                    problems.append(f"work-precision hover text {title!r}: error {match.group(3)} is not {error:.4g}")
            caption = re.search(r"<figcaption>(.*?)</figcaption>", figure, re.S)
            if not caption or re.search(r"[{}\[\]]", caption.group(1)):
                problems.append(f"work-precision caption is not in words: {caption.group(1)[:200] if caption else None!r}")
            if axis == "evaluations":
                for cases in members.values():
                    for case in cases:
                        in_figure = f'data-wp-line="{html.escape(case["name"], quote=True)}"' in figure
                        if in_figure and not counted(case):
                            problems.append(f"{case['name']}: drawn against evaluations it did not count")
                        if not counted(case) and len(cases) >= 2 and any(map(counted, cases)) and \
                                caption and case["name"] in caption.group(1) and "Not drawn" not in caption.group(1):
                            problems.append(f"{case['name']}: its unknown cost is not named in the caption")


def check_baseline_and_zeros(report, dom, problems):
    """The baseline's points beside each compared series on its claim's plot, and no "max error 0"
    for an inconclusive claim whose errors are zeros it did not measure."""
    for case in report["cases"]:
        for claim in case["claims"]:
            key = html.escape(f"{case['name']}/{claim['id']}", quote=True)
            plot = re.search(r'<svg class="plot"[^>]*data-claim-plot="' + re.escape(key) + r'"[^>]*>(.*?)</svg>', dom, re.S)
            for row in claim.get("baseline", {}).get("series", []):
                if row.get("baseline_h") and plot and \
                        f'data-baseline-series="{html.escape(row["label"], quote=True)}"' not in plot.group(1):
                    problems.append(f"{case['name']}/{claim['id']}: the baseline's errors of {row['label']!r} are not drawn")
            errors = [e for s in claim.get("series", [])[:1] for e in s.get("error", [])]
            if claim["verdict"] == "inconclusive" and errors and all(float(e) == 0 for e in errors):
                row = re.search(r'<tr[^>]*data-claim-row="' + re.escape(key) + r'"[^>]*>(.*?)</tr>', dom, re.S)
                if row and "max error 0" in row.group(1):
                    problems.append(f"{case['name']}/{claim['id']}: 'max error 0' for errors it did not measure")


def check_words_and_ticks(report, dom, problems):
    """What the page says matches what was judged: a legend says "fails" only of a series that
    failed (an undecided one reads "inconclusive"); a claim judged on several series and no order
    (energy-behaviour: the drift and the energy error's size) names each in its findings row, not
    the first alone; a failing claim says what its failures mean once, not once per state; the
    time axis of a plot against t ends at a round tick at or past its last sample."""
    for case in report["cases"]:
        for claim in case["claims"]:
            key = f"{case['name']}/{claim['id']}"
            escaped = re.escape(html.escape(key, quote=True))
            legend = re.search(r'<ul class="legend" data-legend-for="' + escaped + r'">(.*?)</ul>', dom, re.S)
            failed = [s for s in claim.get("series", []) if s.get("holds") is False and not s.get("inconclusive")]
            undecided = [s for s in claim.get("series", []) if s.get("holds") is False and s.get("inconclusive")]
            if legend and not failed and "— fails" in html.unescape(legend.group(1)):
                problems.append(f"{key}: the legend says a series fails, but none failed")
            if legend and undecided and "— inconclusive" not in html.unescape(legend.group(1)):
                problems.append(f"{key}: the legend does not say which series is inconclusive")
            row = re.search(r'<tr[^>]*data-claim-row="' + escaped + r'"[^>]*>(.*?)</tr>', dom, re.S)
            if row and claim.get("observed_order") is None and len(claim.get("series", [])) > 1:
                text = html.unescape(re.sub(r"<[^>]+>", "", row.group(1)))
                for series in claim["series"]:
                    if series["label"] not in text:
                        problems.append(f"{key}: the findings row does not name its series {series['label']!r}")
            if claim.get("explanation", "").count(" is not of order ") > 1:
                problems.append(f"{key}: the explanation repeats what its failures mean "
                                f"({claim['explanation'].count(' is not of order ')} times)")
            runs = claim.get("evidence", {}).get("energy_error_against_t") or []
            plot = re.search(r'data-claim-time-plot="' + escaped + r'"[^>]*>(.*?)</svg>', dom, re.S)
            if not runs or not plot:
                continue
            grid = re.search(r'<g class="tick">(.*?)</g>', plot.group(1), re.S)
            ticks = [float(t) for t in re.findall(r'text-anchor="middle">([^<]*)</text>', grid.group(1) if grid else "")]
            last = max((float(t) for run in runs for t in run.get("t", [])), default=0)
            step = ticks[1] - ticks[0] if len(ticks) > 1 else 0
            mantissa = step / 10 ** math.floor(math.log10(step)) if step > 0 else 0
            if (len(ticks) < 3 or ticks[-1] < last * (1 - 1e-9) or
                    not any(abs(mantissa - m) < 1e-6 for m in (1, 2, 2.5, 5)) or
                    any(abs(b - a - step) > 1e-6 * step for a, b in zip(ticks, ticks[1:]))):
                problems.append(f"{key}: the time axis' ticks {ticks} are not round steps to the last sample t = {last}")


# Measures, after layout, every verdict badge against the cell or list it sits in.
BADGE_SCRIPT = """<script>
(() => {
  const outside = [];
  try {
    for (const badge of document.querySelectorAll(".verdict")) {
      const holder = badge.closest("td, li, dd, div, h3, p") || document.body;
      const box = badge.getBoundingClientRect(), cell = holder.getBoundingClientRect();
      if (box.right > cell.right + 0.5 || box.left < cell.left - 0.5)
        outside.push(badge.textContent + " in " + (badge.closest("tr, li") || holder).textContent.slice(0, 60));
    }
  } catch (error) {
    outside.push("the measurement failed: " + error);
  }
  document.body.setAttribute("data-badges-outside", JSON.stringify(outside));
  // A badge's text on more than one line ("INCONCLUS" / "IVE"), and each claim section's border
  // by its verdict: an inconclusive, xfail or xpass claim must not look like a pass.
  const wrapped = [], borders = {};
  try {
    for (const badge of document.querySelectorAll(".verdict")) {
      const range = document.createRange();
      range.selectNodeContents(badge);
      const tops = new Set([...range.getClientRects()].map(r => Math.round(r.top)));
      if (tops.size > 1) wrapped.push(badge.textContent);
    }
    for (const section of document.querySelectorAll("section.claim")) {
      const style = getComputedStyle(section);
      const verdict = [...section.classList].find(c => c !== "claim") || "";
      (borders[verdict] = borders[verdict] || []).push(style.borderLeftColor + " " + style.borderLeftStyle);
    }
  } catch (error) {
    wrapped.push("the measurement failed: " + error);
  }
  document.body.setAttribute("data-badges-wrapped", JSON.stringify(wrapped));
  document.body.setAttribute("data-claim-borders", JSON.stringify(borders));
  // Text past the right margin (a long quoted request, an unbroken path): every text line's box
  // against the page's width; and each claim's plot shown without a click (laid out, not folded).
  const past = [], hidden = [];
  try {
    const margin = document.documentElement.clientWidth;
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    for (let node = walker.nextNode(); node; node = walker.nextNode()) {
      if (!node.textContent.trim() || node.parentElement.closest("details:not([open]) > :not(summary)")) continue;
      const range = document.createRange();
      range.selectNodeContents(node);
      for (const box of range.getClientRects())
        if (box.right > margin + 0.5) {
          const holder = node.parentElement;
          past.push(holder.tagName.toLowerCase() + (holder.className ? "." + holder.className : "") + ": " +
                    node.textContent.trim().slice(0, 80));
          break;
        }
    }
    for (const plot of document.querySelectorAll("svg[data-claim-plot]")) {
      const box = plot.getBoundingClientRect();
      // Inside a closed <details> Chromium may still lay it out (content-visibility): folded all the same.
      const folded = plot.closest("details:not([open])") && !plot.closest("summary");
      if (box.width < 1 || box.height < 1 || folded) hidden.push(plot.getAttribute("data-claim-plot"));
    }
  } catch (error) {
    past.push("the measurement failed: " + error);
  }
  document.body.setAttribute("data-text-past-margin", JSON.stringify(past));
  document.body.setAttribute("data-plots-hidden", JSON.stringify(hidden));
})();
</script>"""


def check_badges_inside_cells(binary, directory, problems):
    """No verdict badge reaches past the cell (or list item) it sits in, at 1280 and 900 px wide:
    the page is laid out by Chromium with a measuring script added to a copy of it."""
    with open(os.path.join(directory, "report.html")) as f:
        page = f.read()
    with tempfile.TemporaryDirectory(prefix="vivv-badges-") as work:
        copy = os.path.join(work, "report.html")
        with open(copy, "w") as f:
            f.write(page.replace("</body>", BADGE_SCRIPT + "</body>"))
        for width in (1280, 900):
            dom = chromium(binary, [f"--window-size={width},3000", "--virtual-time-budget=5000", "--dump-dom",
                                    "file://" + copy])
            found = re.search(r'data-badges-outside="([^"]*)"', dom)
            if not found:
                problems.append(f"at {width} px: the badge measurement did not run")
            elif json.loads(html.unescape(found.group(1))):
                problems.append(f"at {width} px: verdict badges outside their cells: {html.unescape(found.group(1))[:400]}")
            wrapped = re.search(r'data-badges-wrapped="([^"]*)"', dom)
            if wrapped and json.loads(html.unescape(wrapped.group(1))):
                problems.append(f"at {width} px: verdict badges broken over lines: {html.unescape(wrapped.group(1))[:200]}")
            for attribute, what in (("data-text-past-margin", "text past the right margin"),
                                    ("data-plots-hidden", "claim plots not shown without a click")):
                found = re.search(attribute + r'="([^"]*)"', dom)
                if not found:
                    problems.append(f"at {width} px: the layout measurement did not run")
                elif json.loads(html.unescape(found.group(1))):
                    problems.append(f"at {width} px: {what}: {html.unescape(found.group(1))[:400]}")
            borders = re.search(r'data-claim-borders="([^"]*)"', dom)
            borders = json.loads(html.unescape(borders.group(1))) if borders else {}
            passing = set(borders.get("pass", []))
            for verdict, styles in borders.items():
                if verdict != "pass" and passing & set(styles):
                    problems.append(f"at {width} px: a claim section '{verdict}' has the pass border ({styles[0]})")


def badge_self_test(binary):
    """The badge check's negative control: a nowrap badge in a 40 px cell must be found outside it."""
    if shutil.which(binary) is None:
        return 77
    with tempfile.TemporaryDirectory(prefix="vivv-badge-self-test-") as work:
        with open(os.path.join(work, "report.html"), "w") as f:
            f.write('<!DOCTYPE html><html><body><table style="table-layout: fixed; width: 120px"><tr>'
                    '<td style="width: 40px"><span class="verdict" style="white-space: nowrap">inconclusive'
                    '</span></td><td>why</td></tr></table>'
                    '<div style="width: 60px"><span class="verdict" style="display: inline-block; '
                    'overflow-wrap: anywhere">inconclusive</span></div>'
                    '<section class="claim pass" style="border-left: 5px solid green">a</section>'
                    '<section class="claim inconclusive" style="border-left: 5px solid green">b</section>'
                    '<p style="white-space: nowrap">' + 'request' * 400 + '</p>'
                    '<details><summary>plot</summary><svg data-claim-plot="c/x" width="10" height="10"></svg></details>'
                    '</body></html>')
        problems = []
        check_badges_inside_cells(binary, work, problems)
    found = {what: any(what in p for p in problems) for what in ("outside their cells", "broken over lines",
                                                                 "has the pass border", "text past the right margin",
                                                                 "claim plots not shown")}
    print("badge self-test:", ", ".join(f"{what}: {'found' if seen else 'NOT found'}" for what, seen in found.items()))
    return 0 if all(found.values()) else 1


def main(argv):
    if len(argv) == 3 and argv[2] == "--badge-self-test":
        return badge_self_test(argv[1])
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    binary, directory, screenshot = argv[1:]
    if shutil.which(binary) is None:
        print(f"{binary} not found: install Debian's chromium (bash bootstrap.sh test does)")
        return 77
    with open(os.path.join(directory, "report.json")) as f:
        report = json.load(f)
    expected = [f"{case['name']}/{claim['id']}" for case in report["cases"] for claim in case["claims"]]
    verdicts = Counter(claim["verdict"] for case in report["cases"] for claim in case["claims"])
    page = "file://" + os.path.abspath(os.path.join(directory, "report.html"))

    dom = chromium(binary, ["--dump-dom", page])
    problems = []
    rows, plots = attribute_values(dom, "data-claim-row"), attribute_values(dom, "data-claim-plot")
    for key in expected:
        if rows[key] != 1:
            problems.append(f"{key}: {rows[key]} findings rows, expected 1")
        if plots[key] != 1:
            problems.append(f"{key}: {plots[key]} plots, expected 1")
    for key in set(rows) | set(plots):
        if key not in expected:
            problems.append(f"{key}: row or plot for a claim that is not in report.json")
    # Every plot is an <svg> with at least one plotted point (errors of 0 included).
    for match in re.finditer(r'<svg class="plot"[^>]*data-claim-plot="([^"]*)"[^>]*>(.*?)</svg>', dom, re.S):
        if "data-point=" not in match.group(2):
            problems.append(f"{html.unescape(match.group(1))}: plot without points")
        if re.search(r'="[^"]*\b(nan|inf)\b', match.group(2)):
            problems.append(f"{html.unescape(match.group(1))}: NaN or infinity in the plot")
    # A map of h_max against |w| for every claim whose evidence has h_max_by_speed, none for others.
    mapped, maps = check_evidence_figures(report, dom, "h_max_by_speed", "data-claim-map", "plot map",
                                          "data-map-point", "map of h_max against |w|", problems)
    # Verdicts as text and colour class, one per findings row.
    shown = Counter(re.findall(r'<tr class="row-(pass|fail|inconclusive|error|xfail|xpass)', dom))
    if shown != verdicts:
        problems.append(f"findings rows show verdicts {dict(shown)}, report.json has {dict(verdicts)}")
    # Failures first: every claim that did not pass (or xfail) and every refused case is listed
    # once under "Needs attention", linked to its section; no section when there is none; every
    # verdict badge is a link.
    attention_expected = [f"{case['name']}/{claim['id']}" for case in report["cases"]
                          for claim in case["claims"] if claim["verdict"] not in ("pass", "xfail")]
    attention_expected += [f"{case['name']}/{claim['id']}" for case in report["cases"]
                           for claim in case["claims"]
                           if claim.get("baseline", {}).get("status") == "regressed"]
    listed = attribute_values(dom, "data-attention-claim")
    if sorted(listed.elements()) != sorted(attention_expected):
        problems.append(f"'Needs attention' lists {sorted(listed.elements())}, expected {sorted(attention_expected)}")
    refused_shown = len(re.findall(r'data-attention="refused"', dom))
    if refused_shown != len(report.get("refused", [])):
        problems.append(f"'Needs attention' shows {refused_shown} refused cases, report.json has "
                        f"{len(report.get('refused', []))}")
    has_section = 'id="attention"' in dom
    if has_section != bool(attention_expected or report.get("refused")):
        problems.append(f"'Needs attention' section {'present' if has_section else 'missing'}")
    for match in re.finditer(r'<li data-attention="(?!refused)[^"]*" data-attention-claim="[^"]*">(.*?)</li>', dom, re.S):
        anchor = re.search(r'<a href="#(claim-[0-9]+-[0-9]+)">', match.group(1))
        if not anchor or f'id="{anchor.group(1)}"' not in dom:
            problems.append(f"'Needs attention' entry without a working link: {match.group(1)[:120]}")
        # One line per claim: the verdict, observed against predicted, one sentence; the whole
        # explanation folded under "why".
        shown = html.unescape(re.sub(r"<[^>]+>", "", re.sub(r'<details class="why">.*?</details>', "", match.group(1),
                                                             flags=re.S)))
        if len(shown) > 480:
            problems.append(f"'Needs attention' entry of {len(shown)} characters, not one line: {shown[:120]}")
    badges = re.findall(r'<(\w+) class="verdict v-\w+" data-count="\w+"( href="#\w+")?', dom)
    if not badges or any(tag != "a" or not href for tag, href in badges):
        problems.append(f"verdict badges are not all links: {badges}")
    # No text in a plot runs past its right edge: at 12 px a character of this font is at most
    # about 7 px wide (the legend of series, which can be long, is HTML below the plot).
    for match in re.finditer(r'<svg class="plot[^"]*"[^>]*width="([0-9.]+)"[^>]*data-claim-(?:plot|map)="([^"]*)"[^>]*>(.*?)</svg>', dom, re.S):
        width = float(match.group(1))
        for text in re.finditer(r'<text x="([0-9.]+)"[^>]*>(.*?)</text>', match.group(3), re.S):
            content = html.unescape(re.sub(r"<[^>]+>", "", text.group(2)))
            anchor_end = 'text-anchor="end"' in text.group(0) or 'text-anchor="middle"' in text.group(0)
            if not anchor_end and float(text.group(1)) + 7 * len(content) > width:
                problems.append(f"{html.unescape(match.group(2))}: plot text may be clipped at the right edge: {content!r}")
    legends = attribute_values(dom, "data-legend-for")
    for key in expected:
        if legends[key] != 1:
            problems.append(f"{key}: {legends[key]} series legends below the plot, expected 1")
    # A plot against t for every claim whose evidence has energy_error_against_t (energy-behaviour,
    # modified-energy), with a line per h; none for the others.
    timed, _ = check_evidence_figures(report, dom, "energy_error_against_t", "data-claim-time-plot", "plot time",
                                      "data-time-line", "plot against t", problems)
    energy_claims = [f"{case['name']}/{claim['id']}" for case in report["cases"] for claim in case["claims"]
                     if claim["id"] == "energy-behaviour" and claim["verdict"] != "error"]
    for key in energy_claims:
        if key not in timed:
            problems.append(f"{key}: energy-behaviour without energy_error_against_t evidence")
    # An identity or conserved quantity judged against its tolerance at each h is drawn with that
    # tolerance and without a fitted order.
    for case in report["cases"]:
        for claim in case["claims"]:
            if not any(s.get("rule") == "per-step-tolerance" for s in claim.get("series", [])):
                continue
            key = f"{case['name']}/{claim['id']}"
            match = re.search(r'<svg class="plot"[^>]*data-claim-plot="' + re.escape(html.escape(key, quote=True))
                              + r'"[^>]*>(.*?)</svg>', dom, re.S)
            if not match:
                continue
            if claim.get("evidence", {}).get("per_step") and "data-tolerance-line=" not in match.group(1):
                problems.append(f"{key}: judged against a tolerance at each h, but the plot has no tolerance line")
            if len(claim["series"]) == 1 and "data-fit=" in match.group(1):
                problems.append(f"{key}: an identity plotted with a fitted order")
    check_work_precision(report, dom, problems)
    check_baseline_and_zeros(report, dom, problems)
    check_words_and_ticks(report, dom, problems)
    check_badges_inside_cells(binary, directory, problems)
    # report.csv beside it: one row per point of every series, with the run's cost where counted.
    import csv
    csv_path = os.path.join(directory, "report.csv")
    csv_rows = []
    if not os.path.exists(csv_path):
        problems.append("no report.csv beside report.json")
    else:
        with open(csv_path, newline="") as f:
            csv_rows = list(csv.DictReader(f))
    points = sum(len(s["h"]) for case in report["cases"] for claim in case["claims"] for s in claim["series"])
    if len(csv_rows) != points:
        problems.append(f"report.csv has {len(csv_rows)} rows, report.json {points} points")
    # (vivv counts its own evaluations of L; a program's map has none of them to count)
    vivv_computed = [case for case in report["cases"]
                     if case.get("case_file", {}).get("discretization", {}).get("kind") != "process"]
    if vivv_computed and vivv_computed[0].get("cost") and not any(row["L_evaluations"] for row in csv_rows):
        problems.append("report.csv carries no L evaluations")
    # Each case's facts name its discretization, and a formula's L and L_d as written.
    facts = attribute_values(dom, "data-fact")
    cases_with = lambda test: sum(1 for case in report["cases"] if test(case.get("case_file", {})))
    for fact, test in [("discretization", lambda f: isinstance(f.get("discretization"), dict)),
                       ("L_d", lambda f: isinstance(f.get("discretization"), dict) and "L_d" in f["discretization"]),
                       ("lagrangian", lambda f: "lagrangian" in f.get("system", {}))]:
        if facts[fact] < cases_with(test):
            problems.append(f"{facts[fact]} case facts show {fact}, expected at least {cases_with(test)}")
    # Self-contained: no scripts, stylesheets, images or fonts fetched from anywhere.
    for fetched in re.findall(r'<(?:script|link|img|iframe)\b[^>]*(?:src|href)="([^"]*)"', dom):
        problems.append(f"page loads {fetched}")
    if re.search(r'url\((?!#)', dom):
        problems.append("page refers to an external url(...)")

    for problem in problems:
        print(problem)
    print(f"{len(expected)} claims, {sum(rows.values())} rows, {sum(plots.values())} plots, "
          f"{sum(maps.values())} h_max maps (expected {len(mapped)}) in the rendered DOM")

    chromium(binary, [f"--screenshot={os.path.abspath(screenshot)}", "--window-size=1280,4000", page])
    if not os.path.getsize(screenshot):
        problems.append("empty screenshot")
    print(f"screenshot: {os.path.abspath(screenshot)}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
