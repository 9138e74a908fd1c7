// The report's style sheet: readable on screen, A4 when printed: the header and summary on the
// first page, then each section from a new page and each measurement on a page of its own, figures
// kept whole and scaled to the page (two a page, a volume map sheet one): the page count follows
// from the machine's axes and sheets, not from how long its file's path is. System fonts only: nothing to fetch.
#pragma once

namespace vc::report {

inline constexpr const char* kReportStyle = R"css(
body { font-family: sans-serif; font-size: 10.5pt; line-height: 1.35; color: #1a1a1a; max-width: 190mm;
       margin: 1.5em auto; padding: 0 1em; }
h1 { font-size: 18pt; margin-bottom: 0.2em; }
h2 { font-size: 14pt; border-bottom: 1px solid #999; padding-bottom: 0.15em; margin-top: 1.2em; }
h3 { font-size: 11.5pt; margin: 1em 0 0.3em; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 9.5pt; }
th, td { border: 1px solid #bbb; padding: 0.15em 0.5em; vertical-align: top; }
th { background: #eef1f5; text-align: left; }
table.numeric td + td { text-align: right; font-variant-numeric: tabular-nums; }
td.hash, span.hash { font-family: monospace; font-size: 8.5pt; word-break: break-all; }
figure { margin: 0.8em 0; break-inside: avoid; page-break-inside: avoid; }
figure img { display: block; max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 9pt; color: #444; margin-top: 0.3em; }
p.statement { font-weight: bold; background: #eef7ee; border-left: 4px solid #2e7d32; padding: 0.4em 0.6em; }
p.note, ul.notes { font-size: 9pt; color: #444; }
td.pass { color: #1b5e20; font-weight: bold; }
td.fail { color: #b71c1c; font-weight: bold; }
td.missing { color: #666; font-style: italic; }
table.acceptance td:first-child { white-space: nowrap; }
table.numeric.acceptance td:nth-child(2), table.numeric.acceptance td:nth-child(3) { text-align: left; }
nav ol { margin: 0.3em 0; }
@page { size: A4; margin: 12mm 12mm 14mm 12mm; }
@media print {
  body { max-width: none; margin: 0; padding: 0; font-size: 10pt; }
  section { break-before: page; page-break-before: always; }
  div.measurement + div.measurement { break-before: page; page-break-before: always; }
  figure img { width: auto; max-width: 100%; }
  figure.half img { max-height: 112mm; }
  figure.full img { max-height: 235mm; }
  h2, h3 { break-after: avoid; page-break-after: avoid; }
  tr { break-inside: avoid; page-break-inside: avoid; }
}
)css";

}  // namespace vc::report
