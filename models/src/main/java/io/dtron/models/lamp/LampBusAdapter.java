package io.dtron.models.lamp;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import io.dtron.model.TestInterface;
import java.util.Map;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The {@link SmartLamp} as a bus adapter, for TRON's {@code LightContr.xml} with {@code LightContr.trn} on a DTRON
 * bus ({@code dtron run LightContr.xml --interface LightContr.trn --adapter io.dtron.models.lamp.LampBusAdapter}):
 * at each run start a fresh lamp of the adapter's variant runs on the bus's {@link RunClock} (its timers at run
 * times, in the run's time unit); the inputs {@code grasp} and {@code release} are applied as their listener returns
 * (the acknowledgement the tester places them by), and each reported level is published on {@code level} with the
 * time it happened as its event time. The variants are the lamp's: {@code correct} (the default), {@code late}, ...
 */
public final class LampBusAdapter implements DtronAdapter {
    /** The lamp's inputs and its output, as on the bus. */
    static final IDtronChannel GRASP = IDtronChannel.of("grasp");
    static final IDtronChannel RELEASE = IDtronChannel.of("release");
    static final IDtronChannel LEVEL = IDtronChannel.of("level", "adapLevel");

    private static final Logger LOG = LoggerFactory.getLogger(LampBusAdapter.class);

    private final String variant;
    private Dtron dtron;
    /** The lamp of the current run; null between runs. */
    private SmartLamp lamp;

    /** The correct lamp. */
    public LampBusAdapter() {
        this(SmartLamp.VARIANTS.get(0));
    }

    /**
     * The lamp of the named variant.
     *
     * @throws IllegalArgumentException if {@code variant} is none of {@link SmartLamp#VARIANTS}
     */
    public LampBusAdapter(String variant) {
        new SmartLamp(variant); // checks the name
        this.variant = variant;
    }

    @Override
    public synchronized void start(Dtron bus) {
        dtron = bus;
        bus.declareOutputs(LEVEL);
        bus.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                newRun();
            }
        });
        bus.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                endRun();
            }
        });
        for (IDtronChannel input : new IDtronChannel[] {GRASP, RELEASE}) {
            bus.addDtronListener(new DtronListener(input) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    perform(new Event(message.getChannelName(), message.getVariables()));
                }
            });
        }
    }

    /** Stops the lamp; later messages are ignored. */
    @Override
    public synchronized void close() {
        endRun();
        dtron = null;
    }

    private synchronized void newRun() {
        endRun();
        lamp = new SmartLamp(variant);
        lamp.start(new BusContext(dtron.runClock(), lamp));
    }

    private synchronized void endRun() {
        if (lamp != null) {
            lamp.stop();
            lamp = null;
        }
    }

    private synchronized void perform(Event input) {
        if (lamp != null && dtron.runClock().isRunning()) {
            lamp.perform(input);
        }
    }

    /** The lamp's side of a run on the bus: the run clock, and its reports published as they happen. */
    private final class BusContext implements AdapterContext {
        private final RunClock clock;
        private final SmartLamp of;

        BusContext(RunClock clock, SmartLamp of) {
            this.clock = clock;
            this.of = of;
        }

        @Override
        public void report(Event output) {
            long happened = dtron.currentTimeNanos();
            try {
                dtron.send(LEVEL.constructValued(Map.copyOf(output.values())), happened);
            } catch (DtronException e) {
                LOG.warn("Cannot publish {}: {}", output, e.getMessage());
            } catch (IllegalStateException e) {
                // closed
            }
        }

        @Override
        public void report(Event output, long eventMicros) {
            report(output);
        }

        @Override
        public void inputApplied(long ordinal, long eventMicros) {
        }

        @Override
        public void inconclusive(String reason) {
            LOG.warn("The lamp cannot go on: {}", reason);
        }

        @Override
        public TestClock clock() {
            return new TestClock() {
                @Override
                public long nowMicros() {
                    return clock.nowNanos() / 1000;
                }

                @Override
                public Scheduled schedule(long delayMicros, Runnable task) {
                    RunClock.Task t = clock.scheduleAtNanos(clock.nowNanos() + delayMicros * 1000, () -> {
                        synchronized (LampBusAdapter.this) {
                            if (lamp == of) {
                                task.run();
                            }
                        }
                    });
                    return t::cancel;
                }
            };
        }

        @Override
        public TestInterface testInterface() {
            throw new UnsupportedOperationException("the lamp on the bus knows its channels");
        }

        @Override
        public long timeUnitMicros() {
            return clock.timeUnitMicros();
        }
    }
}
