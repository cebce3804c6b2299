package io.dtron.cli;

import io.dtron.bridge.BusRun;
import io.dtron.bridge.ChannelDelay;
import io.dtron.engine.ObservableWindow;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Optional;

/**
 * The timing of a bus run as {@code dtron run} reports it: the delays measured before time 0, the reorder window
 * ({@code --delta}) they give, whether they eat into the model's narrowest observable window, and at the end what
 * the run saw.
 */
final class BusTiming {
    /** Delays that take more than this share of the narrowest window are worth a warning. */
    private static final double WARN_SHARE = 0.2;
    /** The share of the narrowest window that a suggested time unit leaves to the delays. */
    private static final double FIT_SHARE = 0.1;

    private BusTiming() {
    }

    /** The line printed before time 0: the delays measured and the reorder window. */
    static String delaysLine(BusRun.Delays delays, long windowMicros, boolean auto) {
        String measured = delays.messages() == 0
                ? "no message of an adapter could be measured (adapters send their clock offset once they know the"
                        + " tester)"
                : String.format(Locale.ROOT, "up to %s over %d messages of %d adapter%s (clock error up to %s)",
                        millis(delays.maxDelayNanos() / 1000), delays.messages(), delays.members(),
                        delays.members() == 1 ? "" : "s", millis(delays.maxErrorNanos() / 1000));
        String window = auto
                ? "auto: " + BusRun.AUTO_WINDOW_DELAY_FACTOR + " x the longest delay + 2 x the clock error, at"
                        + " least " + millis(BusRun.AUTO_WINDOW_FLOOR_MICROS) + "; widened during the run when a"
                        + " message takes more than half of it"
                : "--delta";
        return "dtron run: delays on the bus before the run: " + measured + "; reorder window (Delta) "
                + millis(windowMicros) + " (" + window + ")";
    }

    /**
     * The line printed after the probes before time 0: how many rounds, for how long, that each took the way of an
     * input, and why they stopped (steady, or the time limit), with the longest round trip of the last rounds;
     * {@code warmedUp} when the engine warmed up meanwhile.
     */
    static String probingLine(BusRun.Probing probing, boolean warmedUp) {
        if (probing.rounds() == 0) {
            return "dtron run: no adapter on the bus to probe before the run";
        }
        return String.format(Locale.ROOT, "dtron run: probed the adapters in %d rounds over %.2f s%s, each probe an"
                + " input that reaches no listener, %s (the last"
                + " rounds' round trips up to %s); each input is sent at least its adapters' round trip ahead of its"
                + " time when they hold inputs until then, else aimed that far inside the end of its window, or the"
                + " 99th percentile of its channel's delays once inputs are acknowledged",
                probing.rounds(), probing.millis() / 1000.0, warmedUp ? " while the engine warmed up" : "",
                probing.steady() ? "until their round trips were steady" : "until the limit, their round trips still"
                        + " uneven", millis(probing.lastMicros()));
    }

    /**
     * A warning when the delays measured take more than a fifth of the model's narrowest observable window at this
     * time unit, with the time unit that would leave them a tenth of it.
     */
    static Optional<String> windowWarning(Optional<ObservableWindow> narrowest, BusRun.Delays delays,
            long unitMicros) {
        if (narrowest.isEmpty() || delays.messages() == 0) {
            return Optional.empty();
        }
        ObservableWindow window = narrowest.get();
        double delayMicros = (delays.maxDelayNanos() + delays.maxErrorNanos()) / 1000.0;
        double widthMicros = (double) window.width() * unitMicros;
        if (window.width() == 0) {
            return Optional.of("dtron run: warning: the observable action " + window + " must happen at an exact"
                    + " time, but the bus's delays measured up to " + millis(Math.round(delayMicros)) + ": its"
                    + " verdicts depend on the timing of the bus and the hosts, at any time unit");
        }
        if (delayMicros <= WARN_SHARE * widthMicros) {
            return Optional.empty();
        }
        long fitting = niceCeil(delayMicros / (FIT_SHARE * window.width()));
        return Optional.of(String.format(Locale.ROOT, "dtron run: warning: the narrowest time window of an observable"
                + " action, %s, is %d time units = %s at %d us per unit; the bus's delays measured before the run (up"
                + " to %s with the clock error) take %.0f%% of it, so the timing of the bus and the hosts may decide"
                + " verdicts; a time unit of %d us or more keeps them under %.0f%%", window, window.width(),
                millis(Math.round(widthMicros)), unitMicros, millis(Math.round(delayMicros)),
                100 * delayMicros / widthMicros, fitting, 100 * FIT_SHARE));
    }

    /** The lines printed after the verdict: the window in the end, its widenings, and the largest delays. */
    static List<String> summary(BusRun run) {
        boolean auto = run.reorderWindowAutomatic();
        List<String> lines = new ArrayList<>();
        List<String> widenings = run.widenings();
        lines.add("reorder window (Delta): " + millis(run.reorderWindowMicros()) + (auto ? " (auto)" : " (--delta)")
                + (widenings.isEmpty() ? (auto ? ", not widened" : "") : ", widened " + String.join("; ", widenings)));
        runDelays(run).ifPresent(lines::add);
        return lines;
    }

    /** The line of the delays measured in the run, per channel and direction, when some were. */
    static Optional<String> runDelays(BusRun run) {
        List<ChannelDelay> delays = run.runDelays();
        if (delays.isEmpty()) {
            return Optional.empty();
        }
        List<String> parts = new ArrayList<>();
        delays.forEach(d -> parts.add(d.direction() + " " + d.channel() + " " + millis(d.lowMicros()) + " to "
                + millis(d.highMicros()) + " (" + d.count() + ")"));
        return Optional.of("delays in the run (inputs published to applied, outputs produced to received): "
                + String.join(", ", parts));
    }

    /**
     * Writes the run's delays per channel and direction as JSON, for {@code dtron delta --delta-from}: the model, the
     * time unit, the run id and one entry per channel and direction measured.
     */
    static String deltaReport(Path model, long unitMicros, String runId, List<ChannelDelay> delays) {
        StringBuilder json = new StringBuilder("{\n  \"model\": ").append(JsonTrace.quote(model.toString()))
                .append(",\n  \"timeUnitMicros\": ").append(unitMicros).append(",\n  \"runId\": ")
                .append(JsonTrace.quote(runId)).append(",\n  \"channels\": [");
        for (int i = 0; i < delays.size(); i++) {
            ChannelDelay d = delays.get(i);
            json.append(i == 0 ? "\n" : ",\n").append("    {\"channel\": ").append(JsonTrace.quote(d.channel()))
                    .append(", \"direction\": \"").append(d.direction()).append("\", \"count\": ").append(d.count())
                    .append(", \"lowMicros\": ").append(d.lowMicros()).append(", \"highMicros\": ")
                    .append(d.highMicros()).append('}');
        }
        return json.append(delays.isEmpty() ? "]\n}\n" : "\n  ]\n}\n").toString();
    }

    /** 0.420 ms, 12.0 ms, 50 ms. */
    static String millis(long micros) {
        double ms = micros / 1000.0;
        return ms >= 10 ? String.format(Locale.ROOT, "%.1f ms", ms).replace(".0 ms", " ms")
                : String.format(Locale.ROOT, "%.3f ms", ms);
    }

    /** The smallest of 1, 2 and 5 times a power of ten at or above {@code value}. */
    static long niceCeil(double value) {
        long power = 1;
        while (true) {
            for (long step : new long[] {1, 2, 5}) {
                if (step * power >= value) {
                    return step * power;
                }
            }
            power *= 10;
        }
    }
}
