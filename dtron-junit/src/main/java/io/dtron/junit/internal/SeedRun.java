package io.dtron.junit.internal;

import io.dtron.engine.Adapter;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.Steering;
import io.dtron.engine.Strategy;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.junit.DtronRun;
import io.dtron.report.ReportPage;
import io.dtron.report.RunRecorder;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.lang.reflect.Method;
import java.util.List;
import java.util.Optional;
import org.junit.jupiter.api.extension.Extension;
import org.junit.jupiter.api.extension.ExtensionContext;
import org.junit.jupiter.api.extension.InvocationInterceptor;
import org.junit.jupiter.api.extension.ParameterContext;
import org.junit.jupiter.api.extension.ParameterResolver;
import org.junit.jupiter.api.extension.ReflectiveInvocationContext;
import org.junit.jupiter.api.extension.TestTemplateInvocationContext;
import org.opentest4j.AssertionFailedError;

/**
 * One run of a {@code @DtronTest} method: its display name carries the seed (and the goal); it hands the method its
 * {@link DtronRun} (or, over the bus, its {@code DtronBusRun}) and checks afterwards that the method tested.
 */
final class SeedRun implements TestTemplateInvocationContext, ParameterResolver, InvocationInterceptor {
    private final DtronExtension.Plan plan;
    private boolean tested;

    SeedRun(DtronExtension.Plan plan) {
        this.plan = plan;
    }

    @Override
    public String getDisplayName(int invocationIndex) {
        return "seed " + plan.seed() + plan.goal().map(g -> ", goal " + g).orElse("");
    }

    @Override
    public List<Extension> getAdditionalExtensions() {
        return List.of(this);
    }

    @Override
    public boolean supportsParameter(ParameterContext parameter, ExtensionContext context) {
        Class<?> type = parameter.getParameter().getType();
        return plan.bus() == null ? type == DtronRun.class : type.getName().equals(BusSettings.RUN);
    }

    @Override
    public Object resolveParameter(ParameterContext parameter, ExtensionContext context) {
        // the bus's run is made only for a method that asks for it: its class needs dtron-core
        return plan.bus() == null ? new Run() : BusSeedRun.of(this);
    }

    @Override
    public void interceptTestTemplateMethod(Invocation<Void> invocation,
                                            ReflectiveInvocationContext<Method> invocationContext,
                                            ExtensionContext extensionContext) throws Throwable {
        invocation.proceed();
        if (!tested) {
            throw new AssertionFailedError("the @DtronTest method returned without testing: call run.test(system)"
                    + " with the system under test" + (plan.bus() == null ? "" : " (over the bus, with its adapters)"));
        }
    }

    DtronExtension.Plan plan() {
        return plan;
    }

    /**
     * Marks this run as tested.
     *
     * @throws IllegalStateException if it was already
     */
    void claim() {
        if (tested) {
            throw new IllegalStateException("this run tested already: call run.test once per run");
        }
        tested = true;
    }

    /** The options of this run: the method's, with this run's seed. */
    TestOptions options() {
        TestOptions base = plan.options();
        return new TestOptions(plan.seed(), base.timeUnitMicros(), base.timeout(), base.delayPolicy(),
                base.delayBound(), base.virtualTime());
    }

    /**
     * Tests {@code system} with {@code options}, writes the run's record and page, stores or takes out the seed, and
     * returns the result when it PASSED; {@code against} ends the record's first line (empty, or what was tested).
     *
     * @throws AssertionFailedError if the run is FAILED
     * @throws Inconclusive if it is INCONCLUSIVE
     */
    TestResult judge(Adapter system, TestOptions options, String against) {
        DtronExtension.Model model = plan.model();
        OnlineTester tester = new OnlineTester(model.network(), model.testInterface(), system, options);
        plan.goal().ifPresent(g -> tester.steer(Steering.of(Strategy.GOAL, List.of(g))));
        RunRecord record = new RunRecord("dtron: " + model.name() + ", seed " + plan.seed()
                + plan.goal().map(g -> ", goal " + g).orElse("") + ", " + options.timeout() + " time units of "
                + options.timeUnitMicros() + " us in " + (options.virtualTime() ? "virtual" : "real") + " time"
                + against, options.timeUnitMicros());
        tester.addListener(record);
        io.dtron.report.RunRecord page = new io.dtron.report.RunRecord(model.name(), model.network(),
                model.layout(), model.layoutNote());
        page.start(plan.seed(), options.timeUnitMicros(), options.timeout(), options.virtualTime());
        tester.addListener(new RunRecorder(page));
        TestResult result = tester.run();
        record.write(result, plan.report());
        try {
            ReportPage.write(page, plan.page());
        } catch (IOException e) {
            throw new UncheckedIOException("cannot write the run's page " + plan.page() + ": " + e.getMessage(), e);
        }
        boolean passed = result.verdict() == Verdict.PASSED;
        plan.store().record(plan.key(), plan.seed(), passed);
        if (passed) {
            return result;
        }
        String message = result.verdict() + " with seed " + plan.seed() + ": " + result.explanation()
                + "\n(the seed runs first next time, from " + plan.store().file() + "; the run: " + plan.report()
                + ", its page: " + plan.page() + ")";
        System.out.println("dtron: " + message);
        if (result.verdict() == Verdict.FAILED) {
            throw new AssertionFailedError(message);
        }
        throw new Inconclusive(message);
    }

    /** The {@link DtronRun} of this invocation: the system in the test's JVM. */
    private final class Run implements DtronRun {
        @Override
        public long seed() {
            return plan.seed();
        }

        @Override
        public Optional<String> goal() {
            return plan.goal();
        }

        @Override
        public TestResult test(Adapter system) {
            claim();
            return judge(system, options(), "");
        }
    }
}
