#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# test_apt.sh — scripts/apt.sh against a fake apt-get that fails the way a
# mirror mid-sync does: updates that fail some times then pass, updates that
# never pass while install works, and an install that never works.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin"
# The fake: FAIL_UPDATES updates fail before one passes (-1: all fail);
# INSTALL_OK=0 makes every install fail. Each call is logged.
cat >"$work/bin/apt-get" <<'FAKE'
#!/usr/bin/env bash
echo "$1" >>"$LOG"
case "$1" in
update)
    n=$(grep -c '^update$' "$LOG")
    if [ "$FAIL_UPDATES" -lt 0 ] || [ "$n" -le "$FAIL_UPDATES" ]; then
        echo "E: Failed to fetch .../binary-armhf/Packages.xz  File has unexpected size (1) != (2). Mirror sync in progress?" >&2
        exit 100
    fi ;;
install) [ "$INSTALL_OK" = 1 ] || exit 100 ;;
esac
FAKE
chmod +x "$work/bin/apt-get"
export PATH="$work/bin:$PATH" LOG="$work/log" SNELL_APT_TRIES=3 SNELL_APT_DELAY=0
. "$root/scripts/apt.sh"
fails=0
check() { # check NAME CONDITION...
    if "${@:2}"; then echo "ok: $1"; else echo "FAIL: $1 (calls: $(tr '\n' ' ' <"$LOG"))"; fails=$((fails + 1)); fi
}
count() { grep -c "^$1\$" "$LOG" || true; }

: >"$LOG"; export FAIL_UPDATES=2 INSTALL_OK=1
rc=0; snell_apt_update 2>/dev/null || rc=$?
check "update passes on its third try" test "$rc" = 0 -a "$(count update)" = 3

: >"$LOG"; export FAIL_UPDATES=-1
rc=0; snell_apt_update 2>"$work/err" || rc=$?
check "update that never passes returns 1 after 3 tries" test "$rc" = 1 -a "$(count update)" = 3
check "and says it goes on" grep -q "going on with the package lists" "$work/err"

: >"$LOG"
rc=0; snell_apt_install blender 2>/dev/null || rc=$?
check "install goes on after a failed index" test "$rc" = 0 -a "$(count install)" = 1

: >"$LOG"; export FAIL_UPDATES=0 INSTALL_OK=0
rc=0; snell_apt_install blender 2>"$work/err" || rc=$?
check "install that never works fails after 3 tries" test "$rc" = 1 -a "$(count install)" = 3
check "and names the packages" grep -q "could not install blender" "$work/err"

[ "$fails" = 0 ]
