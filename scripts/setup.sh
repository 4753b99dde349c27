#!/usr/bin/env bash
# Installs the Debian 12 packages ddafem needs, only those that are missing.
# Idempotent: with everything present it only runs dpkg queries (well under a second).
set -euo pipefail

packages=(
  build-essential cmake git pkg-config clang-format
  libdeal.ii-dev          # deal.II 9.4: Trilinos 13.2, PETSc, p4est, MPI, HDF5, UMFPACK, CGAL, Boost
  libeigen3-dev           # small dense algebra, sparse Cholesky
  libyaml-cpp-dev         # scene files
  nlohmann-json3-dev      # summary.json and verification records
  libcli11-dev            # the command line (subcommands, --help, repeatable --set)
  libhdf5-dev             # HDF5 (the OpenMPI build, the one deal.II links) for histories.h5
  mpi-default-dev         # mpi.h, which the OpenMPI build's hdf5.h includes
  mpi-default-bin         # mpirun: the distributed far field (tests fem.distributed_np*, bench)
  libmumps-dev            # MUMPS (also a deal.II dependency): the distributed far field's block solves
  libsuitesparse-dev      # KLU (blocks and far field), CHOLMOD (far field)
  libtbb-dev              # threads (common/parallel)
  libboost-serialization-dev  # checkpoints (common/checkpoint_archive.h; deal.II's needs it too)
  libcgal-dev libgmp-dev libmpfr-dev
  libgtest-dev googletest # tests
  clang libclang-rt-14-dev llvm  # scripts/sanitize.sh: sanitizers, libFuzzer, llvm-symbolizer
  python3 python3-numpy python3-matplotlib python3-h5py  # plots
  python3-pil ffmpeg      # tools/animate.py: GIF frames, MP4
  # tools/paraview_open.py, tested headless (pvpython, xvfb-run). python3-paraview also gives
  # /usr/bin/python3 VTK's modules (vtkmodules: tests/tools/check_vtk_readers.py's XML readers);
  # it conflicts with python3-vtk9, which installing it removes.
  paraview python3-paraview xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
