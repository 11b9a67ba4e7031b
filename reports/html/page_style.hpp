// The report page's style sheet (report.html is one self-contained page: no network).
#pragma once

namespace vivv::html {

inline const char* const page_style = R"css(
:root { --ink: #1d2430; --muted: #5b6576; --rule: #d8dde6; --panel: #f6f8fb;
        --pass: #11612b; --pass-bg: #dcf3e2; --fail: #a40e26; --fail-bg: #fde2e5;
        --error: #8a4b00; --error-bg: #fff0d1; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
       font: 14px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", Arial, sans-serif; }
main { max-width: 1240px; margin: 0 auto; padding: 20px 28px 60px; }
h1 { font-size: 24px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 36px 0 8px; padding-top: 10px; border-top: 2px solid var(--ink); }
h3 { font-size: 16px; margin: 0 0 6px; display: flex; gap: 10px; align-items: center; flex-wrap: wrap; }
a { color: #0b4f8a; text-decoration: none; } a:hover { text-decoration: underline; }
code, pre, .mono { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12.5px; }
pre { background: var(--panel); padding: 8px 10px; overflow-x: auto; border-radius: 4px; }
.lede { color: var(--muted); margin: 0 0 14px; }
.summary { display: flex; gap: 10px; margin: 10px 0 16px; flex-wrap: wrap; }
.verdict { display: inline-block; padding: 1px 8px; border-radius: 10px; font-weight: 700;
           font-size: 12.5px; letter-spacing: .02em; white-space: nowrap; border: 1px solid; }
.v-pass { color: var(--pass); background: var(--pass-bg); border-color: #9ad2ab; }
.v-fail { color: var(--fail); background: var(--fail-bg); border-color: #f2a3ad; }
.v-error { color: var(--error); background: var(--error-bg); border-color: #f0c36b; }
.v-xfail { color: #4b5563; background: #eef0f3; border-color: #b8bec8; }
.v-xpass { color: var(--fail); background: var(--fail-bg); border-color: #f2a3ad; border-style: dashed; }
.v-inconclusive { color: #5b2a86; background: #efe4fa; border-color: #c3a3e3; }
.note-cell { font-size: 12px; color: var(--muted); }
.summary .verdict { font-size: 15px; padding: 4px 14px; }
table.findings .verdict { white-space: nowrap; font-size: 11.5px; padding: 1px 6px; letter-spacing: 0; }
.attention li { margin: 5px 0; overflow-wrap: anywhere; }
.attention li .verdict { white-space: nowrap; }
details.why { display: inline; font-size: 12px; color: var(--muted); }
details.why[open] { display: block; margin: 2px 0 6px 18px; }
dl.facts dd, p.note, .lede, details pre, table.findings td { overflow-wrap: anywhere; }
ul.legend { list-style: none; padding: 0; margin: 2px 0 8px 72px; max-width: 560px; font-size: 13px; }
ul.legend li { margin: 2px 0; overflow-wrap: anywhere; }
table { border-collapse: collapse; }
table.findings { width: 100%; font-size: 13px; }
table.findings th, table.findings td { border-bottom: 1px solid var(--rule); padding: 5px 7px;
                                       vertical-align: top; text-align: left; }
table.findings th { background: var(--ink); color: #fff; font-weight: 600; position: sticky; top: 0; }
table.findings tr.row-fail td { background: #fff5f6; }
table.findings tr.row-error td { background: #fffaf0; }
table.findings { table-layout: fixed; }
table.findings td.case { font-weight: 600; word-break: break-word; background: #fff !important;
                         border-right: 1px solid var(--rule); }
table.findings tr.first td { border-top: 2px solid #9aa4b5; }
table.findings td .small { font-size: 11.5px; line-height: 1.35; }
table.findings td.num { font-variant-numeric: tabular-nums; }
.small { color: var(--muted); font-size: 12px; }
.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px; margin: 6px 0 10px;
         font-size: 13px; }
.facts dt { color: var(--muted); } .facts dd { margin: 0; }
.claim { border: 1px solid var(--rule); border-left: 5px solid var(--pass); border-radius: 6px;
         padding: 12px 14px; margin: 14px 0; background: #fff; }
.claim.fail { border-left-color: var(--fail); } .claim.error { border-left-color: var(--error); }
.claim.inconclusive { border-left-color: #8a5cc2; border-left-style: dashed; }
.claim.xfail { border-left-color: #8a93a3; } .claim.xpass { border-left-color: var(--fail); border-left-style: dashed; }
.claim-body { display: grid; grid-template-columns: 660px 1fr; gap: 16px; align-items: start; }
@media (max-width: 1100px) { .claim-body { grid-template-columns: 1fr; } }
svg.plot { background: #fff; border: 1px solid var(--rule); border-radius: 4px; max-width: 100%; height: auto; }
svg.plot text { font-size: 12px; fill: var(--ink); }
svg.plot .tick text { fill: var(--muted); font-size: 11px; }
table.series, table.kv, table.points { font-size: 12.5px; margin: 4px 0 8px; }
table.series { width: 100%; }
table.series th, table.series td, table.kv th, table.kv td, table.points th, table.points td {
  border: 1px solid var(--rule); padding: 3px 6px; text-align: left; vertical-align: top; }
table.series th, table.points th, table.kv th { background: var(--panel); font-weight: 600; }
.swatch { display: inline-block; width: 12px; height: 12px; border-radius: 50%; margin-right: 5px;
          vertical-align: -1px; }
details { margin: 6px 0; } summary { cursor: pointer; color: #0b4f8a; }
.note { color: var(--muted); font-size: 12px; margin: 2px 0 6px; }
span.num[title] { border-bottom: 1px dotted #98a2b3; cursor: help; }
figure.map { margin: 10px 0 0; }
figure.map figcaption { font-size: 12.5px; margin: 3px 2px 0; max-width: 640px; }
.fail-text { color: var(--fail); font-weight: 600; }
)css";

}  // namespace vivv::html
