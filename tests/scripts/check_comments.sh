#!/bin/sh
# SPDX-License-Identifier: MIT
# check_comments.sh SOURCE_DIR — comments in src/, include/ and shaders_es/ say
# why (and cite the paper or seed); measurements and history live in
# bench/notes/ and commit messages. Fails, naming file, line and text, on a
# comment with: a commit hash, a date or a UTC time, a load, an issue number
# ("issue 27", "#13"), a result in dB, ms, seconds, a ratio ("1.46x"), a
# percentage ("12% cheaper", "~3%", "was 16%": a share that defines a quantity,
# "1% of the extent", "5% to spare", passes), degrees of error ("0.4 degrees",
# "mean error 2 deg": a bound such as "> 1 degree" passes), or history
# ("was 5", "were a tenth", "It was", "this was", "(before:", "as before", "no
# longer", "used to", "previously", "formerly"); and on a file header (the
# first comment after the SPDX line) over ten lines.
# Comments are found by a small C lexer in awk (strings and character
# literals skipped), so code and messages are not checked. POSIX sh + awk.
set -eu
root=${1:?usage: check_comments.sh SOURCE_DIR}
dirs=""
for d in src include shaders_es; do [ -d "$root/$d" ] && dirs="$dirs $root/$d"; done
# shellcheck disable=SC2086 # dirs: paths without white space
files=$([ -z "$dirs" ] || find $dirs -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.glsl' \
    -o -name '*.frag' -o -name '*.vert' \) | sort)
[ -n "$files" ] || { echo "check_comments.sh: no sources under $root/src, include and shaders_es" >&2; exit 2; }
# shellcheck disable=SC2086 # files: a word list of paths without white space
bad=$(awk -v root="$root/" '
function flag(why, ln,    rel) {
    rel = substr(FILENAME, length(root) + 1)
    printf "%s:%d: %s: %s\n", rel, ln == "" ? FNR : ln, why, text; found = 1
}
function check(t,    n, i, w, words) {
    text = t; found = 0
    n = split(t, words, /[^0-9A-Za-z_]+/)
    for (i = 1; i <= n && !found; i++) {
        w = words[i]
        if (length(w) >= 7 && length(w) <= 40 && w ~ /^[0-9a-f]+$/ && w ~ /[a-f]/ && w ~ /[0-9]/) flag("commit hash")
    }
    lt = tolower(t)
    if (!found && t ~ /20[0-9][0-9]-[01][0-9]-[0-3][0-9]/) flag("date")
    if (!found && t ~ /(^|[^A-Za-z])UTC([^A-Za-z]|$)/) flag("UTC time")
    if (!found && (lt ~ /(^|[^a-z])load[ :=<>~]+[0-9]/ || lt ~ /at load/ || lt ~ /loadavg|load average/)) flag("load")
    if (!found && (lt ~ /issue [0-9]/ || t ~ /#[0-9]/)) flag("issue number")
    if (!found && t ~ /[0-9] ?dB([^A-Za-z]|$)/) flag("dB result")
    if (!found && t ~ /[0-9] ?ms([^A-Za-z]|$)/) flag("ms result")
    if (!found && (lt ~ /[0-9]x single/ || t ~ /[0-9]\.[0-9]+x([^A-Za-z0-9]|$)/)) flag("ratio result")
    if (!found && t ~ /[0-9] s[;,.)]/) flag("seconds result")
    if (!found && (t ~ /~ ?[0-9.]+%/ || lt ~ /(^|[^a-z])(was|were|is|are|out) [0-9.]+%/ || \
        (t ~ /[0-9]%/ && lt !~ /[0-9]%( |-[a-z]+ )?(of|to spare)([^a-z]|$)/))) flag("percent result")
    if (!found && (lt ~ /[0-9]\.[0-9]+ ?(deg|\xc2\xb0)/ || \
        lt ~ /(error|mean|max|median|rms)( of| was| is|:)? ~?[0-9.]+ ?(deg|\xc2\xb0)/)) flag("degrees result")
    if (!found && (lt ~ /\(before[:,]|before:|as before([^a-z]|$)|no longer|used to|previously|formerly/ || \
        lt ~ /(^|[^a-z])(was|were) (~|about |around |only |up to |under |over )?[0-9]/ || \
        lt ~ /(^|[^a-z])(was|were) (a |one )?(tenth|third|quarter|half|fifth|twice)/ || \
        lt ~ /(^|[^a-z])(was|were) (slower|faster|cheaper|dearer|worse|better)/ || \
        lt ~ /(^|[^a-z])this was([^a-z]|$)/ || t ~ /(^|[.;:(] ?|^ *)(It|This|That) (was|were)([^a-z]|$)/)) flag("history")
}
FNR == 1 { state = 0; hs = 0; next_line = 0 } # 0 code, 1 block comment (state survives lines), strings end with their line
# The file header, its first comment after the SPDX line, says what the file
# owns in ten lines at most (docs/ARCHITECTURE.md "Conventions").
FNR == 1 && /SPDX-License-Identifier/ && (/\*\// || /^[ \t]*\/\//) { next_line = 1 }
hs == 0 && !next_line && /^[ \t]*\/\*/ { hs = 1; hn = 0; h0 = FNR }
hs == 0 && !next_line && /^[ \t]*\/\// { hs = 2; hn = 0; h0 = FNR }
hs == 0 && !next_line && /[^ \t]/ && !/^[ \t]*\/[*\/]/ { hs = 3 }
hs == 2 && !/^[ \t]*\/\// { hs = 3; if (hn > 10) { text = hn " lines"; flag("header over 10 lines", h0) } }
hs == 1 || hs == 2 { hn++ }
hs == 1 && /\*\// { hs = 3; if (hn > 10) { text = hn " lines"; flag("header over 10 lines", h0) } }
{ next_line = 0 }
{
    line = $0; out = ""; i = 1; n = length(line); q = ""
    while (i <= n) {
        c = substr(line, i, 1); d = substr(line, i, 2)
        if (state == 1) {
            if (d == "*/") { state = 0; i += 2; continue }
            out = out c; i++; continue
        }
        if (q != "") { if (c == "\\") { i += 2; continue } if (c == q) q = ""; i++; continue }
        if (c == "\"" || c == "\x27") { q = c; i++; continue }
        if (d == "/*") { state = 1; i += 2; out = out " "; continue }
        if (d == "//") { out = out " " substr(line, i + 2); break }
        i++
    }
    if (out ~ /[^ \t*]/) check(out)
}' $files)
if [ -n "$bad" ]; then
    echo "$bad"
    echo "check_comments.sh: $(echo "$bad" | wc -l) comment line(s) in src/, include/ or shaders_es/ carry measurements or history, or a header over ten lines;"
    echo "  say why in a sentence and move the figures to bench/notes/ (with their command, date and load);"
    echo "  a header's longer notes go to docs/ARCHITECTURE.md or docs/methods.md, \"Design notes by file\""
    exit 1
fi
echo "check_comments.sh: $(echo "$files" | wc -l) files, no measurement or history in their comments, headers of ten lines at most"
