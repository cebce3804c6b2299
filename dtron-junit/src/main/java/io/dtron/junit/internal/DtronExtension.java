package io.dtron.junit.internal;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.TestOptions;
import io.dtron.junit.DtronRun;
import io.dtron.junit.DtronTest;
import io.dtron.model.Layout;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.xta.ModelSyntax;
import java.io.IOException;
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.lang.reflect.Method;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ThreadLocalRandom;
import java.util.stream.Stream;
import org.junit.jupiter.api.extension.ExtensionConfigurationException;
import org.junit.jupiter.api.extension.ExtensionContext;
import org.junit.jupiter.api.extension.TestTemplateInvocationContext;
import org.junit.jupiter.api.extension.TestTemplateInvocationContextProvider;

/**
 * Makes the runs of a {@link DtronTest} method: loads its model once, chooses the seeds (those that failed last time
 * first), and gives one invocation per seed and goal, each with its {@link DtronRun}.
 */
public final class DtronExtension implements TestTemplateInvocationContextProvider {
    /** System property: the file of the failed seeds (default {@code .dtron/failed-seeds.properties}). */
    public static final String SEED_FILE = "dtron.seedFile";
    /** System property: the folder of the runs' reports (default {@code target/dtron-reports}). */
    public static final String REPORT_DIRECTORY = "dtron.reportDirectory";
    /**
     * System property: the NATS servers' URLs (comma-separated) of the runs over the bus whose {@link DtronTest#nats()}
     * gives none; unset: JGroups on loopback.
     */
    public static final String NATS = "dtron.nats";

    @Override
    public boolean supportsTestTemplate(ExtensionContext context) {
        return context.getTestMethod().map(m -> m.isAnnotationPresent(DtronTest.class)).orElse(false);
    }

    @Override
    public Stream<TestTemplateInvocationContext> provideTestTemplateInvocationContexts(ExtensionContext context) {
        Method method = context.getRequiredTestMethod();
        Class<?> testClass = context.getRequiredTestClass();
        DtronTest test = method.getAnnotation(DtronTest.class);
        String where = "@DtronTest on " + testClass.getSimpleName() + "." + method.getName();
        Class<?> parameter = method.getParameterCount() == 1 ? method.getParameterTypes()[0] : null;
        if (parameter != DtronRun.class && !BusSettings.RUN.equals(parameter == null ? null : parameter.getName())) {
            throw new ExtensionConfigurationException(where + ": the method takes one parameter, a DtronRun, and"
                    + " calls run.test(system), or, for systems behind bus adapters, a DtronBusRun, and calls"
                    + " run.test(adapters)");
        }
        BusSettings bus = parameter == DtronRun.class ? null : BusSettings.of(test, where);
        if (test.seeds() < 1) {
            throw new ExtensionConfigurationException(where + ": seeds must be at least 1, not " + test.seeds());
        }
        if (test.seed() < -1 || test.timeout() < 0 || test.timeUnit() < 0) {
            throw new ExtensionConfigurationException(where + ": seed must be 0 or more (or -1 for new seeds), timeout"
                    + " and timeUnit 0 (the default) or more");
        }
        Path base = Path.of(System.getProperty("basedir", System.getProperty("user.dir")));
        Model model = load(testClass, test, base, where);
        TestOptions options;
        try {
            long unit = test.timeUnit() > 0 ? test.timeUnit() : orElse(model.testInterface().timeUnitMicros(), 1000);
            long timeout = test.timeout() > 0 ? test.timeout() : orElse(model.testInterface().timeout(), 1000);
            options = new TestOptions(0, unit, timeout, DelayPolicy.RANDOM, 0, bus == null && test.virtualTime());
        } catch (IllegalArgumentException e) {
            throw new ExtensionConfigurationException(where + ": " + e.getMessage());
        }
        SeedStore store = new SeedStore(base.resolve(System.getProperty(SEED_FILE,
                ".dtron/failed-seeds.properties")));
        String name = testClass.getName() + "#" + method.getName();
        List<String> goals = List.of(test.goals());
        // a key per goal: a seed may fail toward one goal and pass toward another
        List<String> keys = goals.isEmpty() ? List.of(name) : goals.stream().map(g -> name + " " + g).toList();
        Set<Long> failed = new LinkedHashSet<>();
        keys.forEach(k -> failed.addAll(store.failed(k)));
        for (long seed : failed) {
            System.out.println("dtron: " + testClass.getSimpleName() + "." + method.getName() + ": seed " + seed
                    + " did not pass last time; it runs first (" + store.file() + ")");
        }
        Set<Long> seeds = new LinkedHashSet<>(failed);
        for (long next = test.seed(); seeds.size() < Math.max(test.seeds(), failed.size()); next++) {
            seeds.add(test.seed() >= 0 ? next : ThreadLocalRandom.current().nextLong(1L << 32));
        }
        Path reports = base.resolve(System.getProperty(REPORT_DIRECTORY, "target/dtron-reports"))
                .resolve(testClass.getName());
        List<TestTemplateInvocationContext> runs = new ArrayList<>();
        for (long seed : seeds) {
            if (goals.isEmpty()) {
                runs.add(new SeedRun(new Plan(model, options, bus, seed, Optional.empty(), store, keys.get(0),
                        reports.resolve(method.getName() + "-seed-" + seed + ".txt"))));
            }
            for (int g = 0; g < goals.size(); g++) {
                runs.add(new SeedRun(new Plan(model, options, bus, seed, Optional.of(goals.get(g)), store,
                        keys.get(g), reports.resolve(method.getName() + "-seed-" + seed + "-goal-" + (g + 1)
                        + ".txt"))));
            }
        }
        return runs.stream();
    }

    private static long orElse(Long value, long fallback) {
        return value != null ? value : fallback;
    }

    /**
     * The model and its test interface, with the name they were given by, and its drawing for the runs' pages (null,
     * with {@code layoutNote} saying why, when it could not be read).
     */
    record Model(String name, Network network, TestInterface testInterface, Layout layout, String layoutNote) {
    }

    /**
     * What one run needs; {@code bus} is null for a system in the test's JVM; {@code key} names its test method (and
     * goal) in the store of failed seeds.
     */
    record Plan(Model model, TestOptions options, BusSettings bus, long seed, Optional<String> goal, SeedStore store,
                String key, Path report) {
        /** The run's HTML page: beside its text record, {@code .html} for {@code .txt}. */
        Path page() {
            String name = report.getFileName().toString();
            return report.resolveSibling(name.substring(0, name.length() - ".txt".length()) + ".html");
        }
    }

    private static Model load(Class<?> testClass, DtronTest test, Path base, String where) {
        try {
            String model = resource(testClass, test.model());
            Path modelFile = model != null ? null : file(testClass, test.model(), base, where, "model");
            Network network = model != null ? ModelLoader.loadResource(testClass.getClassLoader(), model)
                    : ModelLoader.load(modelFile);
            TestInterface testInterface;
            if (test.interfaceFile().isEmpty()) {
                testInterface = TestInterface.fromNames(network);
            } else if (resource(testClass, test.interfaceFile()) != null) {
                try (InputStream in = testClass.getResourceAsStream(test.interfaceFile())) {
                    testInterface = TestInterface.fromText(network, test.interfaceFile(),
                            new String(in.readAllBytes(), StandardCharsets.UTF_8));
                }
            } else {
                testInterface = TestInterface.fromFile(network, file(testClass, test.interfaceFile(), base, where,
                        "interfaceFile"));
            }
            Layout layout = null;
            String layoutNote = null;
            try {
                layout = modelFile != null ? Layout.read(modelFile) : resourceLayout(testClass, model);
            } catch (ModelException | IOException e) {
                layoutNote = "the model's drawing could not be read: " + e.getMessage().lines().findFirst().orElse("");
            }
            return new Model(test.model(), network, testInterface, layout, layoutNote);
        } catch (ModelException e) {
            throw new ExtensionConfigurationException(where + ": " + e.getMessage());
        } catch (IOException e) {
            throw new UncheckedIOException(where + ": cannot read " + test.interfaceFile() + ": " + e.getMessage(), e);
        }
    }

    /** The drawing of the model that is the resource {@code resource}. */
    private static Layout resourceLayout(Class<?> testClass, String resource) throws IOException, ModelException {
        try (InputStream in = testClass.getClassLoader().getResourceAsStream(resource)) {
            return Layout.of(resource, ModelSyntax.decode(in.readAllBytes()));
        }
    }

    /** The classpath name of resource {@code name} beside {@code testClass} (or absolute), or null if there is none. */
    private static String resource(Class<?> testClass, String name) {
        String path = resourcePath(testClass, name);
        return testClass.getClassLoader().getResource(path) != null ? path : null;
    }

    private static String resourcePath(Class<?> testClass, String name) {
        String pkg = testClass.getPackageName().replace('.', '/');
        return name.startsWith("/") ? name.substring(1) : pkg.isEmpty() ? name : pkg + "/" + name;
    }

    /** The file {@code name} in {@code base}; fails the test's configuration clearly when there is none. */
    private static Path file(Class<?> testClass, String name, Path base, String where, String attribute) {
        Path file = base.resolve(name);
        if (Files.isRegularFile(file)) {
            return file;
        }
        throw new ExtensionConfigurationException(where + ": " + attribute + " '" + name + "' is neither a resource on"
                + " the classpath (" + resourcePath(testClass, name) + ") nor a file (" + file + ")");
    }
}
