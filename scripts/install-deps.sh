#!/usr/bin/env bash
# Installs every Debian 12 package igm needs to build, test and fuzz (the solvers: SuiteSparse
# CHOLMOD, oneTBB, Spectra, CBC; GNU parallel: the test
# of `igm batch` run by parallel; pybind11 and python3-*: the Python module igm and its tests,
# built for Debian's /usr/bin/python3).
# `install-deps.sh core`: only what building `igm` needs (scripts/run.sh, the first set-up command).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
PKGS="build-essential cmake pkg-config libgmp-dev libboost-dev libeigen3-dev libsuitesparse-dev libtbb-dev libspectra-dev
  coinor-libcbc-dev"
if [ "${1:-all}" != core ]; then
  PKGS="$PKGS doctest-dev clang libclang-rt-14-dev parallel pybind11-dev python3-pybind11 python3-numpy python3-pytest
  python3-dev python3-venv python3-pip python3-setuptools python3-wheel"
fi
missing=""
for p in $PKGS; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ] || [ "${IGM_FORCE_APT:-0}" = 1 ]; then
  echo "[install-deps] apt-get install$missing"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends $PKGS
else
  echo "[install-deps] all packages present"
fi
