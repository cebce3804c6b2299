package io.dtron.report;

import io.dtron.engine.Event;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestResult;
import java.util.List;

/** Fills a {@link RunRecord} from a tester as its run goes on: add it with {@code OnlineTester#addListener}. */
public final class RunRecorder implements TestListener {
    private final RunRecord record;

    /** A recorder filling {@code record}. */
    public RunRecorder(RunRecord record) {
        this.record = record;
    }

    @Override
    public void inputApplied(Event input, long micros) {
        record.event(true, micros, input.channel(), input.values());
    }

    @Override
    public void outputWindow(Event output, long micros, long earliestMicros, long latestMicros) {
        record.window(earliestMicros, latestMicros);
    }

    @Override
    public void outputObserved(Event output, long micros) {
        record.event(false, micros, output.channel(), output.values());
    }

    @Override
    public void waiting(long nowMicros, long untilMicros, Until until) {
        record.due(nowMicros, until == Until.OUTPUT_DEADLINE ? untilMicros : -1);
    }

    @Override
    public void edgesTaken(Event event, boolean input, long micros, List<String> certainly, List<String> possibly) {
        record.edges(micros, certainly, possibly);
    }

    @Override
    public void finished(TestResult result) {
        record.verdict(result.verdict().name(), result.explanation(), result.durationMicros(), result.inputs(),
                result.outputs());
        if (result.coverage() != null) {
            record.coverage(result.coverage());
        }
    }
}
