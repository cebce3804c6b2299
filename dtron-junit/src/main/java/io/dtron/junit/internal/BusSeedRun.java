package io.dtron.junit.internal;

import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusTest;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.junit.DtronBusRun;
import java.net.InetAddress;
import java.util.List;
import java.util.Optional;
import java.util.UUID;
import org.junit.jupiter.api.extension.ExtensionConfigurationException;

/**
 * The {@link DtronBusRun} of one invocation: the run's bus (a fresh cluster name unless the test names one), the
 * tester and the adapters on it for the time of the run ({@link BusTest}), judged as a run in the test's JVM is. The
 * only class of dtron-junit that needs dtron-core; loaded only for methods that take a {@code DtronBusRun}.
 */
final class BusSeedRun implements DtronBusRun {
    private final SeedRun invocation;
    private final BusSettings settings;
    private final String cluster;

    private BusSeedRun(SeedRun invocation) {
        this.invocation = invocation;
        this.settings = invocation.plan().bus();
        this.cluster = settings.cluster().isEmpty() ? "dtron-junit-" + UUID.randomUUID().toString().substring(0, 8)
                : settings.cluster();
    }

    static DtronBusRun of(SeedRun invocation) {
        return new BusSeedRun(invocation);
    }

    @Override
    public long seed() {
        return invocation.plan().seed();
    }

    @Override
    public Optional<String> goal() {
        return invocation.plan().goal();
    }

    @Override
    public String cluster() {
        return cluster;
    }

    @Override
    public DtronOptions.Builder memberOptions() {
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster);
        return settings.nats().isEmpty() ? options.bindAddress(InetAddress.getLoopbackAddress())
                : options.natsServers(settings.nats());
    }

    @Override
    public TestResult test(DtronAdapter... adapters) {
        invocation.claim();
        String where = "bus '" + cluster + "' on " + (settings.nats().isEmpty()
                ? InetAddress.getLoopbackAddress().getHostAddress() : String.join(",", settings.nats()));
        BusTest bus;
        try {
            bus = BusTest.open(invocation.plan().model().testInterface(), this::memberOptions, List.of(adapters),
                    where);
        } catch (IllegalArgumentException e) {
            throw new ExtensionConfigurationException(invocation.plan().model().name() + ": " + e.getMessage());
        } catch (DtronException e) {
            throw new IllegalStateException("cannot join " + where + ": " + e.getMessage()
                    + (e.getCause() == null ? "" : ": " + e.getCause().getMessage()), e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted while joining " + where, e);
        }
        try (bus) {
            TestOptions options;
            try {
                options = bus.prepare(invocation.options(), settings.busWait());
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new IllegalStateException("interrupted while preparing the run on " + where, e);
            }
            return invocation.judge(bus.adapter(), options, " over " + where);
        }
    }
}
