package io.dtron.junit.internal;

import io.dtron.junit.DtronTest;
import java.time.Duration;
import java.util.List;
import java.util.stream.Stream;
import org.junit.jupiter.api.extension.ExtensionConfigurationException;

/**
 * How the runs of a {@code @DtronTest} method that takes a {@code DtronBusRun} reach their bus, from its annotation.
 * Names nothing of the bus's classes, so that a test suite without dtron-core loads it.
 *
 * @param cluster the cluster name, or empty for a fresh one every run
 * @param nats    the NATS servers' URLs (the annotation's, else those of system property {@value
 *                DtronExtension#NATS}), or none for JGroups on loopback
 * @param busWait how long a run waits until every channel of the model is served
 */
record BusSettings(String cluster, List<String> nats, Duration busWait) {
    /** The parameter type that asks for runs over the bus. */
    static final String RUN = "io.dtron.junit.DtronBusRun";
    /** A class of dtron-core that runs over the bus need. */
    private static final String CORE = "io.dtron.bridge.BusTest";

    /**
     * The settings of {@code test}.
     *
     * @throws ExtensionConfigurationException if dtron-core is not on the test classpath, or a setting is wrong
     */
    static BusSettings of(DtronTest test, String where) {
        try {
            Class.forName(CORE, false, BusSettings.class.getClassLoader());
        } catch (ClassNotFoundException | LinkageError e) {
            throw new ExtensionConfigurationException(where + ": a DtronBusRun tests over the DTRON bus, which needs"
                    + " the artifact io.dtron:dtron-core on the test classpath: add it as a test dependency, of the"
                    + " version of dtron-junit");
        }
        if (test.busWait() < 1) {
            throw new ExtensionConfigurationException(where + ": busWait must be at least 1 second, not "
                    + test.busWait());
        }
        if (!test.cluster().equals(test.cluster().strip()) || test.cluster().contains(" ")) {
            throw new ExtensionConfigurationException(where + ": cluster '" + test.cluster() + "' has a space in it");
        }
        List<String> nats = List.of(test.nats());
        if (nats.stream().anyMatch(String::isBlank)) {
            throw new ExtensionConfigurationException(where + ": nats has a blank URL");
        }
        if (nats.isEmpty()) {
            nats = Stream.of(System.getProperty(DtronExtension.NATS, "").split(",")).map(String::strip)
                    .filter(url -> !url.isEmpty()).toList();
        }
        return new BusSettings(test.cluster(), nats, Duration.ofSeconds(test.busWait()));
    }
}
