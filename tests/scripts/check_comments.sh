#!/bin/sh
# SPDX-License-Identifier: MIT
# check_comments.sh SOURCE_DIR — comments in src/ and shaders_es/ say why
# (and cite the paper or seed); measurements and history live in bench/notes/
# and commit messages. Fails, naming file, line and text, on a comment with:
#   a commit hash (a 7-40 digit hex word with letters and digits), a date
#   (YYYY-MM-DD) or a UTC time, a load ("load 1.5", "at load", loadavg), an
#   issue number ("issue 27", "#13"), a measured result in dB, ms, seconds
#   or a ratio ("1.46x"), or history ("(before:", "before:", "as before", "no longer",
#   "used to", "previously", "formerly").
# Comments are found by a small C lexer in awk (strings and character
# literals skipped), so code and messages are not checked. POSIX sh + awk.
set -eu
root=${1:?usage: check_comments.sh SOURCE_DIR}
files=$(find "$root/src" "$root/shaders_es" -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.glsl' \
    -o -name '*.frag' -o -name '*.vert' \) | sort)
[ -n "$files" ] || { echo "check_comments.sh: no sources under $root/src and $root/shaders_es" >&2; exit 2; }
# shellcheck disable=SC2086 # files: a word list of paths without white space
bad=$(awk -v root="$root/" '
function flag(why) { printf "%s:%d: %s: %s\n", substr(FILENAME, length(root) + 1), FNR, why, text; found = 1 }
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
    if (!found && (lt ~ /\(before[:,]|before:|as before([^a-z]|$)|no longer|used to|previously|formerly/)) flag("history")
}
FNR == 1 { state = 0 } # 0 code, 1 block comment (state survives lines), strings end with their line
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
    echo "check_comments.sh: $(echo "$bad" | wc -l) comment line(s) in src/ or shaders_es/ carry measurements or history;"
    echo "  say why in a sentence and move the figures to bench/notes/ (with their command, date and load)"
    exit 1
fi
echo "check_comments.sh: $(echo "$files" | wc -l) files, no measurement or history in their comments"
