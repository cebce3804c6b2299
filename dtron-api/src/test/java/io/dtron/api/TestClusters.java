package io.dtron.api;

import java.util.UUID;

/** Cluster names and options that keep tests from joining each other. */
final class TestClusters {
    private TestClusters() {
    }

    static String uniqueName(String test) {
        return test + "-" + UUID.randomUUID().toString().substring(0, 8);
    }

    static DtronOptions.Builder inJvm(String cluster) {
        return DtronOptions.builder().clusterName(cluster).inJvm(true);
    }
}
