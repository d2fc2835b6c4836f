#!/usr/bin/env bash
# scripts/install-deps.sh waits while another installation holds apt's lock and fails at
# once on any other apt error. A stand-in apt-get (APT_GET) answers "Could not get lock" to
# its first two calls; REFMAP_DEPS_PACKAGES names a package that is not installed, so the
# script has something to install. Nothing real is installed or locked.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ "$(id -u)" != 0 ]; then echo "install-deps test: needs root (the script uses sudo otherwise); skipped"; exit 0; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/apt-get" <<'FAKE'
#!/usr/bin/env bash
n=$(cat "$STATE/calls" 2>/dev/null || echo 0); echo $((n + 1)) > "$STATE/calls"
echo "$*" >> "$STATE/args"
if [ "$MODE" = busy ] && [ "$n" -lt 2 ]; then
  echo "E: Could not get lock /var/lib/apt/lists/lock. It is held by process 4242 (apt-get)" >&2; exit 100
fi
if [ "$MODE" = broken ]; then echo "E: Unable to locate package refmap-no-such-package" >&2; exit 100; fi
exit 0
FAKE
chmod +x "$work/apt-get"
fail() { echo "FAIL: $*"; exit 1; }

# 1. busy twice, then through: both apt calls run, two waits reported
mkdir "$work/busy"
out=$(STATE="$work/busy" MODE=busy APT_GET="$work/apt-get" APT_WAIT_S=0 \
      REFMAP_DEPS_PACKAGES=refmap-no-such-package bash "$root/scripts/install-deps.sh" 2>&1) || fail "busy: exit $?: $out"
[ "$(grep -c 'apt is busy' <<< "$out")" = 2 ] || fail "busy: expected two waits: $out"
[ "$(cat "$work/busy/calls")" = 4 ] || fail "busy: expected 4 apt calls (2 refused, update, install), got $(cat "$work/busy/calls")"
grep -q "^-o DPkg::Lock::Timeout=600 install .*refmap-no-such-package" "$work/busy/args" || fail "busy: install not called: $(cat "$work/busy/args")"

# 2. another error: fails at once, no waiting
mkdir "$work/broken"
if out=$(STATE="$work/broken" MODE=broken APT_GET="$work/apt-get" APT_WAIT_S=0 \
         REFMAP_DEPS_PACKAGES=refmap-no-such-package bash "$root/scripts/install-deps.sh" 2>&1); then
  fail "broken: exit 0"
fi
grep -q 'apt is busy' <<< "$out" && fail "broken: waited on a non-lock error: $out"
[ "$(cat "$work/broken/calls")" = 1 ] || fail "broken: expected 1 apt call, got $(cat "$work/broken/calls")"
echo "install-deps test: 2 passed, 0 failed"
