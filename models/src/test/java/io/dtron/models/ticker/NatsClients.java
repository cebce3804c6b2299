package io.dtron.models.ticker;

import io.dtron.testsupport.NatsServer;
import java.io.IOException;
import java.nio.file.Path;
import java.util.concurrent.TimeUnit;

/**
 * The Python and C clients for the tests that run them: a Python with the {@code dtron} package ({@code
 * $DTRON_PYTHON}, which {@code scripts/test} makes, else {@code python3} if it has the package), and programs of the C
 * client built with CMake into {@code target/clients-c}. A test whose client cannot be had is skipped, or fails under
 * {@code DTRON_REQUIRE_TOOLS=1}.
 */
public final class NatsClients {
    /** The Python client's folder. */
    public static final Path PYTHON = Path.of("../clients/python").toAbsolutePath().normalize();
    /** The C client's folder. */
    static final Path C = Path.of("../clients/c").toAbsolutePath().normalize();

    private NatsClients() {
    }

    /** A Python with the dtron package. */
    public static String python() throws InterruptedException {
        String python = System.getenv().getOrDefault("DTRON_PYTHON", "python3");
        boolean usable;
        try {
            Process probe = new ProcessBuilder(python, "-c", "import dtron, nats").redirectErrorStream(true).start();
            usable = probe.waitFor(30, TimeUnit.SECONDS) && probe.exitValue() == 0;
        } catch (IOException e) {
            usable = false;
        }
        NatsServer.requireTool(usable, "a Python with the dtron package (pip install ./clients/python; DTRON_PYTHON)");
        return python;
    }

    /** Builds a program of the C client (a CMake target) and returns its path. */
    static synchronized Path cProgram(String target) throws InterruptedException {
        Path build = Path.of("target/clients-c").toAbsolutePath();
        Path log = Path.of("target/clients-c.log").toAbsolutePath();
        boolean built;
        try {
            Process configure = new ProcessBuilder("cmake", "-S", C.toString(), "-B", build.toString())
                    .redirectErrorStream(true).redirectOutput(log.toFile()).start();
            built = configure.waitFor(120, TimeUnit.SECONDS) && configure.exitValue() == 0;
            if (built) {
                Process make = new ProcessBuilder("cmake", "--build", build.toString(), "--target", target)
                        .redirectErrorStream(true).redirectOutput(ProcessBuilder.Redirect.appendTo(log.toFile()))
                        .start();
                built = make.waitFor(300, TimeUnit.SECONDS) && make.exitValue() == 0;
            }
        } catch (IOException e) {
            built = false;
        }
        NatsServer.requireTool(built, "cmake with libnats-dev, libprotobuf-c-dev and protobuf-c-compiler (see " + log
                + ")");
        return build.resolve(target);
    }
}
