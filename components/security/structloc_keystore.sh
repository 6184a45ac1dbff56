#!/usr/bin/env bash
# structloc_keystore: makes a DDS Security keystore for structloc, laid out as
# SROS2 lays out its own (ros2 security create_keystore / create_enclave), so
# that ROS 2 users find what they know:
#   KEYSTORE/private/ca.key.pem       the CA's private key: keep it off robots
#   KEYSTORE/public/ca.cert.pem       the CA (identity and permissions CA)
#   KEYSTORE/enclaves/governance.p7s  the domain's rules, signed by the CA
#   KEYSTORE/enclaves/NAME/           one enclave per identity: cert.pem,
#       key.pem, permissions.p7s (its grant, signed by the CA), and copies of
#       governance.p7s, identity_ca.cert.pem and permissions_ca.cert.pem
# A component uses one enclave: --security-enclave KEYSTORE/enclaves/NAME
# (launch argument security_keystore:=KEYSTORE).
#
# Governance: unauthenticated participants are refused, joining needs a grant,
# discovery, liveliness and every topic's data and metadata are encrypted, and
# every topic is read- and write-access controlled.
# Permissions (default DENY; topics with or without a ROS 2 namespace, rt/X and
# rt/*/X):
#   simulator     publishes scan, odom, wheel_encoders, ground_truth,
#                 tf_static (the laser's mounting), diagnostics; subscribes
#                 cmd_vel (a laser or robot driver takes this identity on a
#                 real robot)
#   localisation  publishes pose, tf, structloc/status, structloc/features,
#                 structloc/hypotheses, diagnostics; subscribes scan, odom,
#                 tf_static, initialpose, reinitialize_global_localization
#   calibration   publishes structloc/calibration, diagnostics; subscribes
#                 wheel_encoders, pose
#   operator      publishes initialpose, cmd_vel,
#                 reinitialize_global_localization; subscribes every topic
#                 (structloc watch, dashboards, ros2 topic echo)
#
# Usage: structloc_keystore KEYSTORE [--days N] [--organisation O] [--country C]
#                                    [--domains MIN-MAX]
# KEYSTORE must not exist yet (nothing is overwritten). To rotate identities,
# make a new keystore, install its enclaves on every host and restart the
# components (docs/guides/security.md).
set -euo pipefail
set -f  # no globbing: "*" is a topic pattern here, not file names

usage() {
  echo "usage: $0 KEYSTORE [--days N] [--organisation O] [--country CC] [--domains MIN-MAX]" >&2
  exit 2
}

[ $# -ge 1 ] || usage
keystore="$1"
shift
days=3650
organisation=structloc
country=CH
domains=0-232
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || usage
  case "$1" in
    --days) days="$2" ;;
    --organisation) organisation="$2" ;;
    --country) country="$2" ;;
    --domains) domains="$2" ;;
    *)
      echo "structloc_keystore: unknown option '$1'" >&2
      usage
      ;;
  esac
  shift 2
done
[[ "$days" =~ ^[1-9][0-9]{0,4}$ ]] || { echo "structloc_keystore: --days '$days' must be 1..99999" >&2; exit 2; }
[[ "$country" =~ ^[A-Z]{2}$ ]] || { echo "structloc_keystore: --country '$country' must be two capital letters" >&2; exit 2; }
[[ "$organisation" =~ ^[A-Za-z0-9_.\ -]{1,64}$ ]] ||
  { echo "structloc_keystore: --organisation '$organisation' may hold letters, digits, space, _ . - only" >&2; exit 2; }
[[ "$domains" =~ ^([0-9]{1,3})-([0-9]{1,3})$ ]] && [ "${BASH_REMATCH[1]}" -le "${BASH_REMATCH[2]}" ] &&
  [ "${BASH_REMATCH[2]}" -le 232 ] ||
  { echo "structloc_keystore: --domains '$domains' must be MIN-MAX within 0-232" >&2; exit 2; }
domain_min="${BASH_REMATCH[1]}"
domain_max="${BASH_REMATCH[2]}"
command -v openssl >/dev/null || { echo "structloc_keystore: openssl is not installed" >&2; exit 1; }
if [ -e "$keystore" ]; then
  echo "structloc_keystore: $keystore exists; choose a new folder (nothing is overwritten)" >&2
  exit 1
fi

umask 077
mkdir -p "$keystore/private" "$keystore/public" "$keystore/enclaves"
work="$(mktemp -d)"
# On any failure: openssl's own messages, and no half-made keystore left
# behind (a rerun would refuse the existing folder).
trap 'status=$?; if [ "$status" -ne 0 ]; then
  echo "structloc_keystore: failed; openssl said:" >&2; cat "$work/openssl.log" >&2
  rm -rf -- "$keystore"; fi; rm -rf -- "$work"' EXIT
ssl() { openssl "$@" 2>>"$work/openssl.log"; }

ca_key="$keystore/private/ca.key.pem"
ca_cert="$keystore/public/ca.cert.pem"
# Certificates and grants are valid from a day back, so that a host whose
# clock runs behind the one that made the keystore still accepts them.
# The same two instants in OpenSSL's and in the permissions' notation.
first="$(date -u -d "-1 day" +%s)"
last="$(date -u -d "+$days days" +%s)"
start_date="$(date -u -d "@$first" +%Y%m%d%H%M%SZ)"
end_date="$(date -u -d "@$last" +%Y%m%d%H%M%SZ)"
not_before="$(date -u -d "@$first" +%Y-%m-%dT%H:%M:%S)"
not_after="$(date -u -d "@$last" +%Y-%m-%dT%H:%M:%S)"

# The subject as OpenSSL's -subj takes it, and as the permissions must spell
# it for Fast DDS (CN, O, C in that order).
subject_arg() { echo "/C=$country/O=$organisation/CN=$1"; }
subject_name() { echo "CN=$1, O=$organisation, C=$country"; }

# OpenSSL's "ca" command, as it alone sets a start date: the CA (self-signed,
# CA:TRUE) and identities (CA:FALSE, as SROS2 makes them), fresh serials.
mkdir "$work/issued"
touch "$work/index.txt"
ssl rand -hex 8 >"$work/serial"
cat >"$work/ca.cnf" <<CNF
[ ca ]
default_ca = signer
[ signer ]
database = $work/index.txt
new_certs_dir = $work/issued
serial = $work/serial
default_md = sha256
policy = subject
unique_subject = no
email_in_dn = no
[ subject ]
countryName = supplied
organizationName = supplied
commonName = supplied
[ ca_extensions ]
basicConstraints = critical, CA:TRUE
subjectKeyIdentifier = hash
authorityKeyIdentifier = keyid:always
[ identity_extensions ]
basicConstraints = CA:FALSE
subjectKeyIdentifier = hash
authorityKeyIdentifier = keyid, issuer
CNF
issue() {  # issue KEY CN OUT EXTENSIONS [ca options...]
  local key="$1" cn="$2" out="$3" extensions="$4"
  shift 4
  ssl req -new -key "$key" -subj "$(subject_arg "$cn")" -out "$work/request.pem"
  ssl ca -batch -notext -config "$work/ca.cnf" -in "$work/request.pem" -out "$out" \
    -extensions "$extensions" -startdate "$start_date" -enddate "$end_date" "$@"
}

ssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$ca_key"
issue "$ca_key" "structloc CA" "$ca_cert" ca_extensions -selfsign -keyfile "$ca_key"

sign() {  # sign FILE.xml -> FILE.p7s with the CA
  ssl smime -sign -text -in "$1" -out "${1%.xml}.p7s" -signer "$ca_cert" -inkey "$ca_key"
}

cat >"$keystore/enclaves/governance.xml" <<GOV
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>$domain_min</min><max>$domain_max</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>SIGN</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
GOV
sign "$keystore/enclaves/governance.xml"

topic_list() {  # topic_list NAME... -> <topic> lines, plain and namespaced
  local t
  for t in "$@"; do
    if [ "$t" = "*" ]; then
      echo "          <topic>*</topic>"
    else
      echo "          <topic>rt/$t</topic>"
      echo "          <topic>rt/*/$t</topic>"
    fi
  done
}

# enclave NAME "PUBLISHED TOPICS" "SUBSCRIBED TOPICS"
enclave() {
  local name="$1" dir="$keystore/enclaves/$1"
  mkdir -p "$dir"
  ssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$dir/key.pem"
  issue "$dir/key.pem" "$name" "$dir/cert.pem" identity_extensions -cert "$ca_cert" -keyfile "$ca_key"
  # shellcheck disable=SC2086
  cat >"$dir/permissions.xml" <<PERM
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$name">
      <subject_name>$(subject_name "$name")</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>
      <allow_rule>
        <domains><id_range><min>$domain_min</min><max>$domain_max</max></id_range></domains>
        <publish>
          <topics>
$(topic_list $2)
          </topics>
        </publish>
        <subscribe>
          <topics>
$(topic_list $3)
          </topics>
        </subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
PERM
  sign "$dir/permissions.xml"
  cp "$keystore/enclaves/governance.p7s" "$dir/governance.p7s"
  cp "$ca_cert" "$dir/identity_ca.cert.pem"
  cp "$ca_cert" "$dir/permissions_ca.cert.pem"
}

enclave simulator "scan odom wheel_encoders ground_truth tf_static diagnostics" "cmd_vel"
enclave localisation "pose tf structloc/status structloc/features structloc/hypotheses diagnostics" \
  "scan odom tf_static initialpose reinitialize_global_localization"
enclave calibration "structloc/calibration diagnostics" "wheel_encoders pose"
enclave operator "initialpose cmd_vel reinitialize_global_localization" "*"

echo "structloc_keystore: $keystore holds a CA and the enclaves simulator, localisation, calibration," \
  "operator (valid $days days, domains $domain_min-$domain_max); keep $ca_key off the robots"
