#!/usr/bin/env bash
# Prints the directory of example-robot-data's URDFs in the peers' environment (setup.sh).
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/common.sh"
peers_require
peers_robots
