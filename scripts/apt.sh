# shellcheck shell=bash
# apt.sh — sourced by the scripts that install packages. A Debian mirror
# caught mid-sync serves an index whose size or hash disagrees with its
# Release file ("File has unexpected size ... Mirror sync in progress?");
# apt-get update then exits non-zero although every other index arrived.
# These helpers retry, then go on with the lists that did arrive: a missing
# security or updates index only means older package versions, and a package
# that really cannot be found still fails at install or download.
#
# SNELL_APT_TRIES (default 3) and SNELL_APT_DELAY (seconds, default 15; the
# n-th retry waits n times that) tune the retries.

# snell_apt_update [apt-get options...]: 0 when an update succeeded, 1 when
# every try failed (the lists that did download are kept by apt).
snell_apt_update() {
    local tries=${SNELL_APT_TRIES:-3} delay=${SNELL_APT_DELAY:-15} i
    for ((i = 1; i <= tries; i++)); do
        if DEBIAN_FRONTEND=noninteractive apt-get update -qq -o Acquire::Retries=3 "$@"; then
            return 0
        fi
        if ((i < tries)); then
            echo "apt: update failed (try $i of $tries); again in $((delay * i)) s" >&2
            sleep $((delay * i))
        fi
    done
    echo "apt: update failed $tries times; going on with the package lists that arrived" >&2
    return 1
}

# snell_apt_install PACKAGE...: update (tolerating a failed index), then
# install; an install that fails (a package list too old for the mirror's
# files) is retried after a fresh update, up to SNELL_APT_TRIES times.
snell_apt_install() {
    local tries=${SNELL_APT_TRIES:-3} delay=${SNELL_APT_DELAY:-15} i
    for ((i = 1; i <= tries; i++)); do
        snell_apt_update || true
        if DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
            -o Acquire::Retries=3 "$@"; then
            return 0
        fi
        if ((i < tries)); then
            echo "apt: install of $* failed (try $i of $tries); again in $((delay * i)) s" >&2
            sleep $((delay * i))
        fi
    done
    echo "apt: could not install $*" >&2
    return 1
}
