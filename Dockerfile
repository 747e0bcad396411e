# FlowScape without root on the host (rootless Podman or Docker): the toolkit built with its
# optional parts off (no oneDNN denoiser, no Python extension, no test suite), installed in
# /usr/local. README "Install without root".
#   podman build -t flowscape .
#   podman run --rm -v "$PWD/out:/out" flowscape gen_flowscape --demo --out /out/demo
FROM debian:12
COPY scripts/install_deps.sh /src/scripts/install_deps.sh
RUN /src/scripts/install_deps.sh --minimal && rm -rf /var/lib/apt/lists/*
COPY . /src
RUN cmake -S /src -B /build -DCMAKE_BUILD_TYPE=Release -DFLOWSCAPE_DENOISER=OFF \
        -DFLOWSCAPE_PYTHON_EXTENSION=OFF -DBUILD_TESTING=OFF \
    && cmake --build /build -j "$(nproc)" && cmake --install /build && rm -rf /build
WORKDIR /out
