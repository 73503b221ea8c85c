#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# make_sysroot.sh arm64|armhf [DIR] — a Debian 12 sysroot for cross builds
# (cmake/toolchains/), made from Debian's own arm64/armhf packages without
# touching the host's package state: a private APT configuration (own sources,
# lists, cache and an empty dpkg status) resolves the dependency closure,
# `apt-get download` fetches it and `dpkg-deb -x` unpacks it into DIR.
# `dpkg --add-architecture` is deliberately not used: making the host
# multi-arch would let APT move the host's own Mesa to match the foreign one.
#
# DIR defaults to build-sysroot/ARCH (git-ignored by /build*/). A stamp keyed by
# the package list makes a rerun with the same list a no-op (remove DIR to
# take newer Debian versions); downloaded .debs stay in DIR.apt/archives, so
# remaking DIR downloads only what changed.
# Needs network access to the mirror (SNELL_SYSROOT_MIRROR, default
# http://deb.debian.org/debian, and its -security twin) and apt, dpkg-deb.
set -euo pipefail

arch=${1:-}
case "$arch" in
arm64 | armhf) ;;
*)
    echo "usage: $0 arm64|armhf [DIR]" >&2
    exit 2
    ;;
esac
root=$(realpath -m "${2:-$(dirname "$0")/../build-sysroot/$arch}")
apt_dir=$root.apt
mirror=${SNELL_SYSROOT_MIRROR:-http://deb.debian.org/debian}
security=${SNELL_SYSROOT_SECURITY_MIRROR:-http://deb.debian.org/debian-security}

# What snell builds and links against (the README's package list, target side),
# and Mesa's drivers so that tests run under qemu-user on llvmpipe; libdrm and gbm for
# snell-kiosk (ports/kms, SNELL_WITH_KMS), which the Pi runs on its KMS display.
PACKAGES=(libc6-dev libstdc++-12-dev
          libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libgbm1 libgbm-dev libdrm-dev
          libcglm-dev libstb-dev libtinygltf-dev nlohmann-json3-dev libmeshoptimizer-dev)

stamp=$root/.snell-sysroot
want="$arch $mirror ${PACKAGES[*]}"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    echo "make_sysroot: $root is up to date"
    exit 0
fi

mkdir -p "$apt_dir"/{lists/partial,archives/partial,sources.list.d,preferences.d}
: >"$apt_dir/status"
cat >"$apt_dir/sources.list" <<SOURCES
deb [arch=$arch signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] $mirror bookworm main
deb [arch=$arch signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] $mirror bookworm-updates main
deb [arch=$arch signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] $security bookworm-security main
SOURCES
cat >"$apt_dir/apt.conf" <<CONF
APT::Architecture "$arch";
APT::Architectures { "$arch"; };
Dir::Etc::SourceList "$apt_dir/sources.list";
Dir::Etc::SourceParts "$apt_dir/sources.list.d";
Dir::Etc::Preferences "$apt_dir/preferences";
Dir::Etc::PreferencesParts "$apt_dir/preferences.d";
Dir::State "$apt_dir";
Dir::State::Lists "$apt_dir/lists";
Dir::State::status "$apt_dir/status";
Dir::Cache "$apt_dir";
Dir::Cache::archives "$apt_dir/archives";
Acquire::Languages "none";
APT::Get::AllowUnauthenticated "false";
CONF
export APT_CONFIG=$apt_dir/apt.conf

echo "make_sysroot: apt-get update ($arch, private lists in $apt_dir)"
. "$(dirname "$0")/apt.sh"
if ! snell_apt_update; then
    # Only the main suite is needed to resolve and fetch the closure; the
    # updates and security suites, when their index failed, just leave older
    # versions in the sysroot.
    compgen -G "$apt_dir/lists/*_dists_bookworm_main_binary-${arch}_Packages*" >/dev/null || {
        echo "make_sysroot: no bookworm main index for $arch; cannot resolve packages" >&2
        exit 1
    }
    echo "make_sysroot: building from the indexes that arrived" >&2
fi

# The closure of real packages (apt-cache prints virtual ones as <name>, and
# alternatives' first choice is taken by --recurse as it lists them).
mapfile -t closure < <(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts \
    --no-breaks --no-replaces --no-enhances "${PACKAGES[@]}" | grep -v '^ ' | grep -v '^<' | sort -u)
# The exact files of this closure (name_version_arch.deb): fetched only when
# not already in the archive folder, and only these are unpacked (older
# versions left there by an earlier run are not).
mapfile -t debs < <(apt-get download --print-uris "${closure[@]}" | awk '{print $2}')
# A download that fails (a mirror mid-sync, a dropped connection) is retried
# for the files still missing.
for try in 1 2 3; do
    fetch=()
    for deb in "${debs[@]}"; do
        [ -f "$apt_dir/archives/$deb" ] || fetch+=("${deb%%_*}")
    done
    echo "make_sysroot: ${#closure[@]} packages, ${#fetch[@]} to download"
    [ ${#fetch[@]} -gt 0 ] || break
    [ "$try" = 1 ] || sleep $((${SNELL_APT_DELAY:-15} * (try - 1)))
    (cd "$apt_dir/archives" && apt-get download -qq -o Acquire::Retries=3 "${fetch[@]}" 2>&1 |
        grep -v "^W: Download is performed unsandboxed" || true)
done
rm -rf "$root"
mkdir -p "$root"
for deb in "${debs[@]}"; do
    [ -f "$apt_dir/archives/$deb" ] || { echo "make_sysroot: $deb was not downloaded" >&2; exit 1; }
    dpkg-deb -x "$apt_dir/archives/$deb" "$root"
done

# Absolute symlinks (e.g. lib*.so -> /lib/...) would point into the host:
# make them relative to the sysroot.
find "$root" -type l -lname '/*' -print0 | while IFS= read -r -d '' link; do
    target=$(readlink "$link")
    ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$root$target")" "$link"
done
printf '%s' "$want" >"$stamp"
echo "make_sysroot: $root ($(du -sh "$root" | cut -f1))"
