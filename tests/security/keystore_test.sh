#!/usr/bin/env bash
# structloc_keystore's own promises (issue 16), checked with openssl: the
# SROS2 layout; every identity certificate signed by the keystore's CA, marked
# CA:FALSE and valid from a day back; every signed document verifying against
# the CA; private keys readable by their owner only; an existing folder
# refused; and a failing openssl step reported with openssl's message and no
# half-made keystore left behind. Everything it creates is removed on exit.
#   keystore_test.sh BUILD_DIR
set -euo pipefail
keystore_bin="$1/bin/structloc_keystore"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failed=0
fail() {
  echo "FAILED: $*"
  failed=1
}

keys="$work/keys"
"$keystore_bin" "$keys" >"$work/make.log" 2>&1 || { cat "$work/make.log"; fail "no keystore made"; exit 1; }
ca="$keys/public/ca.cert.pem"
day_ago=$(($(date +%s) - 23 * 3600))
for identity in simulator localisation calibration operator; do
  dir="$keys/enclaves/$identity"
  for file in cert.pem key.pem permissions.p7s governance.p7s identity_ca.cert.pem \
    permissions_ca.cert.pem; do
    [ -s "$dir/$file" ] || fail "$identity lacks $file"
  done
  openssl verify -CAfile "$ca" "$dir/cert.pem" >/dev/null 2>&1 || fail "$identity's certificate is not the CA's"
  openssl x509 -in "$dir/cert.pem" -noout -ext basicConstraints 2>/dev/null | grep -q "CA:FALSE" ||
    fail "$identity's certificate is not marked CA:FALSE"
  openssl x509 -in "$dir/cert.pem" -noout -subject | grep -q "CN = $identity" ||
    fail "$identity's certificate names another subject"
  not_before=$(date -d "$(openssl x509 -in "$dir/cert.pem" -noout -startdate | cut -d= -f2)" +%s)
  [ "$not_before" -le "$day_ago" ] || fail "$identity's certificate is not valid from a day back"
  openssl smime -verify -in "$dir/permissions.p7s" -CAfile "$ca" -out /dev/null >/dev/null 2>&1 ||
    fail "$identity's permissions do not verify against the CA"
  [ "$(stat -c %a "$dir/key.pem")" = 600 ] || fail "$identity's key is readable by others"
done
openssl smime -verify -in "$keys/enclaves/governance.p7s" -CAfile "$ca" -out /dev/null >/dev/null 2>&1 ||
  fail "the governance does not verify against the CA"
[ "$(stat -c %a "$keys/private")" = 700 ] || fail "the CA key's folder is open to others"

if "$keystore_bin" "$keys" >"$work/again.log" 2>&1 || ! grep -q "exists" "$work/again.log"; then
  fail "an existing keystore was not refused"
fi

# An openssl whose "ca" step fails: the script must say so and leave nothing.
mkdir "$work/fake"
printf '#!/bin/sh\n[ "$1" = ca ] && { echo "simulated openssl failure" >&2; exit 1; }\nexec %s "$@"\n' \
  "$(command -v openssl)" >"$work/fake/openssl"
chmod +x "$work/fake/openssl"
if PATH="$work/fake:$PATH" "$keystore_bin" "$work/broken" >"$work/broken.log" 2>&1; then
  fail "the keystore script succeeded although openssl failed"
fi
grep -q "simulated openssl failure" "$work/broken.log" || fail "openssl's message was not shown"
[ ! -e "$work/broken" ] || fail "a half-made keystore was left behind"

if [ "$failed" -ne 0 ]; then exit 1; fi
echo "PASSED: the keystore's layout, signatures, validity and permissions, and its clean failure"
