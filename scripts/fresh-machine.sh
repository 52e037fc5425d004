#!/usr/bin/env bash
# Tries the README's Quick start the way a new user would: on a clean Debian 12 root.
#   scripts/fresh-machine.sh [--keep] [--root DIR] [--log DIR]
# Makes a fresh Debian 12 (bookworm) root with debootstrap, copies this checkout into it (the
# files git tracks, and untracked ones it does not ignore: no build/, no node_modules/), and
# runs the two commands of the README's "## Quick start" block inside it with chroot, each
# timed, as root with no display. Everything is downloaded and built from scratch, so this is
# not part of CI; run it before claiming the Quick start works. Needs root and the network to
# reach the package registries the host uses (their addresses are read from the host's apt
# sources; the host's certificate store is copied in, so the package clients inside trust
# the same registries the host does).
# --keep leaves the root in place (default: removed at the end); --root picks its folder;
# --log writes each command's full output there (default: <root>.logs).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
keep=0
root=""
logs=""
while [ $# -gt 0 ]; do
    case "$1" in
        --keep) keep=1 ;;
        --root) root=$2; shift ;;
        --log) logs=$2; shift ;;
        -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
        *) echo "fresh-machine.sh: error: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done

say() { printf '[fresh-machine] %s\n' "$*"; }
fail() { echo "fresh-machine.sh: error: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || fail "needs root (debootstrap and chroot)"
if ! command -v debootstrap >/dev/null 2>&1; then
    say "installing debootstrap"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap \
        >/dev/null || fail "could not install debootstrap"
fi

# The Quick start block: the first fenced block after "## Quick start", one command a line.
mapfile -t commands < <(awk '
    /^## / { in_section = ($0 ~ /^## Quick start/) }
    in_section && /^```/ { if (in_block) exit; in_block = 1; next }
    in_section && in_block && NF { print }' "$repo/README.md")
[ ${#commands[@]} -eq 2 ] ||
    fail "README.md's Quick start block should hold exactly two commands, found ${#commands[@]}"

# The Debian mirror the host uses (its first enabled "deb" source).
mirror=$(awk '/^URIs:/ { print $2; exit }' /etc/apt/sources.list.d/*.sources 2>/dev/null || true)
if [ -z "$mirror" ]; then
    mirror=$(awk '$1 == "deb" { print ($2 ~ /^\[/ ? $3 : $2); exit }' /etc/apt/sources.list \
             /etc/apt/sources.list.d/*.list 2>/dev/null || true)
fi
[ -n "$mirror" ] || fail "no Debian mirror found in the host's apt sources"

[ -n "$root" ] || root=$(mktemp -d /var/tmp/luxel-fresh-root.XXXXXX)
[ -n "$logs" ] || logs="$root.logs"
mkdir -p "$root" "$logs"
mounted=()
cleanup() {
    for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
        umount -l "${mounted[i]}" 2>/dev/null || true
    done
    if [ "$keep" -eq 0 ]; then
        rm -rf --one-file-system "$root"
    else
        say "root kept in $root"
    fi
}
trap cleanup EXIT

start=$(date +%s)
say "debootstrap bookworm into $root (log: $logs/debootstrap.log)"
debootstrap --variant=minbase bookworm "$root" "$mirror" >"$logs/debootstrap.log" 2>&1 ||
    { tail -n 20 "$logs/debootstrap.log" >&2; fail "debootstrap failed"; }
say "root made in $(( $(date +%s) - start )) s"

# The host's view of the registries: apt sources and its Acquire settings, name resolution,
# and the certificate store (kept across update-ca-certificates inside, which rebuilds the
# bundle from /usr/local/share/ca-certificates).
cp /etc/resolv.conf "$root/etc/resolv.conf"
rm -f "$root/etc/apt/sources.list"
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] && cp "$f" "$root$f"
done
for f in /etc/apt/apt.conf.d/*; do
    grep -q '^Acquire::' "$f" 2>/dev/null && cp "$f" "$root/etc/apt/apt.conf.d/"
done
mkdir -p "$root/etc/ssl/certs" "$root/usr/local/share/ca-certificates"
cp -L /etc/ssl/certs/ca-certificates.crt "$root/etc/ssl/certs/ca-certificates.crt"
cp -r /usr/local/share/ca-certificates/. "$root/usr/local/share/ca-certificates/" 2>/dev/null || true
[ -f /etc/npmrc ] && cp /etc/npmrc "$root/etc/npmrc"

for fs in proc sys dev dev/pts; do
    mkdir -p "$root/$fs"
    case "$fs" in
        proc) mount -t proc proc "$root/proc" ;;
        sys) mount -t sysfs sys "$root/sys" ;;
        *) mount --bind "/$fs" "$root/$fs" ;;
    esac
    mounted+=("$root/$fs")
done

say "copying the checkout into $root/root/luxel"
mkdir -p "$root/root/luxel"
(cd "$repo" && git ls-files -z --cached --others --exclude-standard |
    tar --null -T - -cf - | tar -xf - -C "$root/root/luxel")

# A new machine's environment: no display, a plain PATH, the certificate bundle for Node.js.
run_in_root() {
    chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb \
        PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
        NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt \
        /bin/bash -c "cd /root/luxel && $1"
}

status=0
results=()
for n in 0 1; do
    command=${commands[n]}
    log="$logs/command-$((n + 1)).log"
    say "command $((n + 1)): $command (log: $log)"
    t0=$(date +%s)
    if run_in_root "$command" >"$log" 2>&1; then
        verdict=passed
    else
        verdict="FAILED (exit $?)"
        status=1
    fi
    seconds=$(( $(date +%s) - t0 ))
    results+=("command $((n + 1)): $verdict in $((seconds / 60)) min $((seconds % 60)) s: $command")
    say "${results[-1]}"
    if [ "$verdict" != passed ]; then
        tail -n 30 "$log" >&2
    fi
done

say "summary ($(nproc) cores, $(( $(date +%s) - start )) s in all):"
printf '  %s\n' "${results[@]}"
exit "$status"
