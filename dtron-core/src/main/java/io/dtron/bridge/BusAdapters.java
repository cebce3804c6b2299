package io.dtron.bridge;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronOptions;
import java.util.ArrayList;
import java.util.List;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The bus adapters a tester runs in its own JVM ({@code dtron run --adapter}, {@link BusTest}), each a member of the
 * bus with a {@link Dtron} of its own. Closing stops them and takes their members off the bus.
 */
public final class BusAdapters implements AutoCloseable {
    private static final Logger LOG = LoggerFactory.getLogger(BusAdapters.class);

    private final Supplier<DtronOptions.Builder> options;
    private final List<DtronAdapter> adapters = new ArrayList<>();
    private final List<Dtron> members = new ArrayList<>();

    /** Adapters that join the bus with the options {@code options} makes, one set for each. */
    public BusAdapters(Supplier<DtronOptions.Builder> options) {
        this.options = options;
    }

    /**
     * Connects an adapter to the bus as a member of its own and starts it.
     *
     * @return its member id
     * @throws io.dtron.api.DtronException if it cannot join the bus
     */
    public String start(DtronAdapter adapter) {
        Dtron member = Dtron.connect(options.get().build());
        members.add(member);
        adapters.add(adapter);
        adapter.start(member);
        return member.getMemberId();
    }

    /** Stops the adapters started and takes their members off the bus; closing twice does nothing more. */
    @Override
    public void close() {
        for (DtronAdapter adapter : adapters) {
            try {
                adapter.close();
            } catch (RuntimeException e) {
                LOG.warn("Adapter {} failed to close: {}", adapter.getClass().getName(), e.toString());
            }
        }
        adapters.clear();
        members.forEach(Dtron::close);
        members.clear();
    }
}
