#!/usr/bin/env bash
# Installs the Debian packages of scripts/packages.txt that a job needs and that are not
# installed yet: the untagged lines and those tagged with JOB.
# Usage: scripts/install_packages.sh JOB   (build, sanitize, static, format or scale)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs=(build sanitize static format scale)
job="${1:-}"
if [[ " ${jobs[*]} " != *" $job "* ]]; then
  echo "install_packages: usage: $0 JOB (one of: ${jobs[*]})" >&2
  exit 2
fi

packages=()
while read -r -a words; do
  ((${#words[@]})) || continue
  for tag in "${words[@]:1}"; do
    if [[ " ${jobs[*]} " != *" $tag "* ]]; then
      echo "install_packages: scripts/packages.txt: unknown job '$tag' for ${words[0]}" >&2
      exit 2
    fi
  done
  if ((${#words[@]} == 1)) || [[ " ${words[*]:1} " == *" $job "* ]]; then
    packages+=("${words[0]}")
  fi
done < <(sed -e 's/#.*//' "$here/scripts/packages.txt")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]})) || exit 0
echo "install_packages: installing ${missing[*]}" >&2
if [[ $(id -u) -eq 0 ]]; then sudo=(); elif command -v sudo >/dev/null; then sudo=(sudo); else
  echo "install_packages: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
