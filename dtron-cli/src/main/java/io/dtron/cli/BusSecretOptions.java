package io.dtron.cli;

import io.dtron.api.DtronOptions;
import java.nio.file.Path;
import java.util.function.Function;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;

/**
 * The option of the bus's secret, {@code --key-file}, mixed into the commands that join a bus, and the member options
 * it makes; {@link OrInsecure} adds {@code --insecure} for the commands that may join a bus without a secret ({@code
 * dtron reload} may not: a controller takes model versions only from a bus with a secret).
 */
class BusSecretOptions {
    @Option(names = "--key-file", paramLabel = "FILE",
            description = "The file holding the bus's secret (default: $DTRON_HOME/bus.key, else ~/.dtron/bus.key,"
                    + " made when missing), which every member of the bus holds; it must be readable by its owner"
                    + " only (chmod 600).")
    private Path keyFile;

    /** Whether an option of the secret was given: they are for a member on the bus. */
    boolean given() {
        return keyFile != null;
    }

    /** Sets the bus's secret of the options on the member's {@code options}, and returns them. */
    DtronOptions.Builder apply(DtronOptions.Builder options) {
        if (keyFile != null) {
            options.keyFile(keyFile);
        }
        return options;
    }

    /** {@code --key-file} or {@code --insecure}, no secret: their check, and the member options they make. */
    static final class OrInsecure extends BusSecretOptions {
        @Option(names = "--insecure",
                description = "Use no secret on the bus, for members that have none: only insecure members are then"
                        + " heard, and anyone who can reach the bus may speak on it.")
        private boolean insecure;

        /** Whether {@code --insecure} was given. */
        boolean insecure() {
            return insecure;
        }

        @Override
        boolean given() {
            return super.given() || insecure;
        }

        /** Checks that the options do not both come: an insecure member has no key file. */
        void check(Function<String, ParameterException> usage) {
            if (super.given() && insecure) {
                throw usage.apply("--insecure uses no secret: leave out --key-file");
            }
        }

        @Override
        DtronOptions.Builder apply(DtronOptions.Builder options) {
            return super.apply(options).insecure(insecure);
        }
    }
}
