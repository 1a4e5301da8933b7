# Sourced by the project's scripts: the built workspace's environment, loopback ROS settings.
# shellcheck shell=bash
SAP_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export PYENV_VERSION=system
set +u
# shellcheck disable=SC1091
source "${SAP_WS:-$SAP_ROOT/build/ws}/devel/setup.bash"
export ROS_IP=127.0.0.1
export ROS_HOSTNAME=127.0.0.1
